#include "studio_server.h"

#include "meander/error.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <new>
#include <optional>
#include <string_view>

namespace meander {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

// Requests one connection may carry, and how long it may wait for the next.
constexpr size_t keep_alive_requests = 100;
constexpr time_t keep_alive_seconds = 5;

// One connection's bytes, from a socket or from memory (StudioServer::serve_bytes), held to
// StudioServerOptions' limits. Debian's httplib (0.11) reads a request line or header
// line of any length into memory, any number of headers, a chunked body without the
// payload limit, and waits as long as a byte comes within each read timeout; here a read
// fails once a request's headers pass max_header bytes or header_timeout, its body
// passes its Content-Length, or it passes request_timeout. httplib answers a failed
// read with 400 or by closing the connection.
class ConnectionStream final : public httplib::Stream {
public:
  ConnectionStream(int socket, const StudioServerOptions& limits) : socket_(socket), limits_(limits) {}
  ConnectionStream(std::string_view input, const StudioServerOptions& limits) : input_(input), limits_(limits) {}

  // Waits up to `idle` for the next request's first byte (false at the end, on silence,
  // or once `open` turns false), then starts that request's budget and clocks.
  template <class Open> bool next_request(std::chrono::milliseconds idle, Open open) {
    const auto deadline = Clock::now() + idle;
    while (pending().empty()) {
      if (socket_ < 0 || !open()) return false;
      // Short waits, so that a stopping server is noticed within 50 ms.
      if (wait(POLLIN, std::min(deadline, Clock::now() + std::chrono::milliseconds(50)))) {
        if (receive() <= 0) return false;
      } else if (Clock::now() >= deadline) {
        return false;
      }
    }
    const auto now = Clock::now();
    header_deadline_ = now + limits_.header_timeout;
    request_deadline_ = now + limits_.request_timeout;
    response_deadline_.reset();
    in_headers_ = true;
    allowed_ = limits_.max_header;
    return true;
  }
  // The headers are in; the body may be `length` bytes and no more. Without a length
  // (a transfer coding, or more than max_upload) no byte of it may be read.
  void start_body(std::optional<uint64_t> length) {
    in_headers_ = false;
    body_known_ = length.has_value();
    allowed_ = length.value_or(0);
  }
  // Whether the request was read to its end, so that the next one starts where it ended.
  bool request_complete() const { return !in_headers_ && body_known_ && allowed_ == 0; }
  const std::string& output() const { return output_; }

  // Whether a read failed because the client was too slow.
  bool too_slow() const { return too_slow_; }

  // Before closing after a request that was not read to its end: lets the client finish
  // sending (the bytes dropped), so that it reads the answer (a 413, a 403) rather than a
  // reset connection. Until the client closes, or sends nothing for idle_timeout, or
  // request_timeout has passed: a deadline of its own would cut off a client slowed by
  // a busy machine.
  void drain() {
    shutdown(socket_, SHUT_WR);
    const auto deadline = Clock::now() + limits_.request_timeout;
    while (wait(POLLIN, deadline) && receive() > 0) {
    }
  }

  bool is_readable() const override { return true; }
  bool is_writable() const override { return true; }

  ssize_t read(char* data, size_t size) override {
    if (allowed_ == 0) return -1;
    if (pending().empty()) {
      if (socket_ < 0) return 0;
      if (!wait(POLLIN, in_headers_ ? header_deadline_ : request_deadline_)) {
        too_slow_ = true;
        return -1;
      }
      if (const ssize_t n = receive(); n <= 0) return n;
    }
    const size_t n = size_t(std::min<uint64_t>({size, allowed_, pending().size()}));
    std::memcpy(data, pending().data(), n);
    taken_ += n;
    allowed_ -= n;
    return ssize_t(n);
  }

  ssize_t write(const char* data, size_t size) override {
    if (socket_ < 0) {
      output_.append(data, size);
      return ssize_t(size);
    }
    if (!response_deadline_) response_deadline_ = Clock::now() + limits_.request_timeout;
    if (!wait(POLLOUT, *response_deadline_)) return -1;
    return send(socket_, data, size, MSG_NOSIGNAL | MSG_DONTWAIT);
  }

  // The studio does not look at addresses.
  void get_remote_ip_and_port(std::string&, int&) const override {}
  void get_local_ip_and_port(std::string&, int&) const override {}
  socket_t socket() const override { return socket_; }

private:
  std::string_view pending() const { return (socket_ < 0 ? input_ : std::string_view(buffer_, filled_)).substr(taken_); }

  // Refills the buffer from the socket once wait() found bytes: their count, 0 at the
  // end, -1 on an error.
  ssize_t receive() {
    const ssize_t n = recv(socket_, buffer_, sizeof buffer_, 0);
    if (n > 0) filled_ = size_t(n), taken_ = 0;
    return n;
  }

  // Whether the socket is ready for `events` before both `deadline` and idle_timeout. A
  // socket ready already is, however late: a thread that was not run for a while (a busy
  // machine) does not fail a client who was on time.
  bool wait(short events, Clock::time_point deadline) const {
    const auto until = std::min(deadline, Clock::now() + limits_.idle_timeout);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now()).count();
      pollfd fd{socket_, events, 0};
      const int ready = poll(&fd, 1, int(std::max<int64_t>(left, 0)));
      if (ready > 0) return true;
      if (ready == 0 || errno != EINTR) return false;
    }
  }

  int socket_ = -1;
  std::string_view input_;
  const StudioServerOptions& limits_;
  char buffer_[4096];
  size_t filled_ = 0, taken_ = 0;
  bool in_headers_ = true, body_known_ = false, too_slow_ = false;
  uint64_t allowed_ = 0; // bytes the request may still send
  Clock::time_point header_deadline_, request_deadline_;
  std::optional<Clock::time_point> response_deadline_;
  std::string output_;
};

// The socket of the connection whose request this thread is answering (-1: none, or
// bytes from memory): what a handler asks whether its client is still there.
thread_local int current_socket = -1;

// Whether the client on `socket` has closed its end (a page that aborted its fetch): it
// waits for no answer any more.
bool client_gone(int socket) {
  pollfd fd{socket, POLLIN | POLLRDHUP, 0};
  if (poll(&fd, 1, 0) <= 0) return false;
  if (fd.revents & (POLLHUP | POLLERR | POLLRDHUP)) return true;
  char byte;
  return recv(socket, &byte, 1, MSG_PEEK | MSG_DONTWAIT) == 0;
}

// httplib's server with its connections served through ConnectionStream, one request
// after another, each prepared before httplib reads its body.
class GuardedServer final : public httplib::Server {
public:
  explicit GuardedServer(const StudioServerOptions& limits) : limits_(limits) {}

  void serve(ConnectionStream& stream) {
    for (size_t count = keep_alive_requests; count > 0; --count) {
      if (!stream.next_request(std::chrono::seconds(keep_alive_seconds), [this] { return svr_sock_ != INVALID_SOCKET; }))
        return;
      bool closed = false;
      current_socket = stream.socket();
      const bool written = process_request(stream, count == 1, closed, [&](httplib::Request& req) { prepare(req, stream); });
      current_socket = -1;
      // A request not read to its end (refused before its body, or cut off) leaves bytes
      // that are not the next request: never parse them as one.
      if (!written || closed || !stream.request_complete()) return;
    }
  }

  // httplib listens with a backlog of 5: a burst of connections (100 uploads at once)
  // overflows it and some are reset. Listening again only lengthens the queue.
  void lengthen_backlog() {
    if (::listen(svr_sock_, SOMAXCONN) != 0) throw IOError("cannot listen: " + std::string(std::strerror(errno)));
  }

private:
  // Called once the headers are in, before routing and the body.
  void prepare(httplib::Request& req, ConnectionStream& stream) const {
    std::optional<uint64_t> length;
    if (req.has_header("Content-Length")) {
      // As httplib reads it; a length it refuses (413) gets no byte of its body read.
      const uint64_t claimed = std::strtoull(req.get_header_value("Content-Length").c_str(), nullptr, 10);
      if (claimed <= limits_.max_upload) length = claimed;
    } else if (!req.has_header("Transfer-Encoding")) {
      // No length and no transfer coding: no body (RFC 9112, 6.3), where httplib would
      // read until the client closes. (A transfer coding is refused before routing.)
      req.set_header("Content-Length", "0");
      length = 0;
    }
    // A Range header of many ranges makes httplib copy the answer once per range.
    req.ranges.clear();
    stream.start_body(length);
  }

  bool process_and_close_socket(socket_t socket) override {
    // httplib writes an answer's headers and body apart: with Nagle's algorithm the body
    // waits for the client's delayed ACK of the headers, 40 ms on every small answer.
    const int on = 1;
    setsockopt(socket, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    ConnectionStream stream(socket, limits_);
    serve(stream);
    if (!stream.request_complete() && !stream.too_slow()) stream.drain();
    shutdown(socket, SHUT_RDWR);
    close(socket);
    return true;
  }

  const StudioServerOptions& limits_;
};

struct Asset {
  std::string bytes;
  std::string type;
};

std::string content_type(const fs::path& path) {
  static const std::map<std::string, std::string> types = {
      {".html", "text/html; charset=utf-8"}, {".js", "text/javascript"}, {".css", "text/css"},
      {".svg", "image/svg+xml"},            {".png", "image/png"},      {".ico", "image/x-icon"},
      {".json", "application/json"},        {".woff2", "font/woff2"},   {".txt", "text/plain; charset=utf-8"}};
  const auto it = types.find(path.extension().string());
  return it == types.end() ? "application/octet-stream" : it->second;
}

// The whole page in memory, keyed by URL path: a request can name only what is here.
std::map<std::string, Asset> read_page(const fs::path& folder) {
  std::map<std::string, Asset> assets;
  std::error_code error;
  if (folder.empty() || !fs::is_directory(folder, error)) return assets;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    if (!in) throw IOError(entry.path().string() + ": cannot open");
    std::string url = "/";
    url += entry.path().lexically_relative(folder).generic_string();
    assets[url] = {std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()),
                   content_type(entry.path())};
  }
  return assets;
}

void send_json(httplib::Response& res, int status, const json& body) {
  res.status = status;
  // Messages quote what the client sent (a path, a file name), which need not be UTF-8;
  // dump() would throw, and from httplib's error handler that ended the process.
  res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, status, {{"error", message}});
}

// The CLI's exit codes as HTTP: a bad option is the client's request (400), a refused
// file is content the server understood but cannot use (422), anything else is ours.
template <class Work> void answer(httplib::Response& res, Work work) {
  try {
    work();
  } catch (const Cancelled&) {
    send_json(res, 409, {{"error", "cancelled: a newer request or a cancel replaced this one"}, {"cancelled", true}});
  } catch (const UsageError& e) {
    send_error(res, 400, e.what());
  } catch (const InputError& e) {
    send_error(res, 422, e.what());
  } catch (const TopologyError& e) {
    send_error(res, 422, e.what());
  } catch (const std::bad_alloc&) {
    send_error(res, 500, "out of memory");
  } catch (const std::exception& e) {
    send_error(res, 500, e.what());
  }
}

json surface_json(const std::string& session, const StudioSurface& surface) {
  if (!surface.picture.empty())
    return {{"session", session},
            {"name", surface.name},
            {"picture", {{"width", surface.picture.width}, {"height", surface.picture.height}}}};
  const PolygonMesh& mesh = surface.repaired.mesh;
  const Box3 box = bounding_box(mesh.positions);
  return {{"session", session},
          {"name", surface.name},
          {"input", {{"vertices", surface.input_vertices}, {"faces", surface.input_faces}}},
          {"vertices", mesh.num_vertices()},
          {"faces", mesh.num_faces()},
          {"bounding_box", {{"min", {box.min.x, box.min.y, box.min.z}}, {"max", {box.max.x, box.max.y, box.max.z}}}},
          {"repairs", surface.repaired.repairs},
          {"notices", surface.repaired.notices}};
}

// Host names (with an optional :port) that name this server.
bool names_this_server(const std::string& bound_host, int port, std::string_view host) {
  const std::string with_port = std::string(":") + std::to_string(port);
  if (host.ends_with(with_port)) host.remove_suffix(with_port.size());
  if (host == "127.0.0.1" || host == "localhost" || host == "[::1]") return true;
  if (bound_host.empty()) return false;
  // An IPv6 address is written in brackets in a Host header.
  if (bound_host.find(':') != std::string::npos)
    return host.size() == bound_host.size() + 2 && host.front() == '[' && host.back() == ']' &&
           host.substr(1, bound_host.size()) == bound_host;
  return host == bound_host;
}

} // namespace

std::string studio_request_refusal(const std::string& bound_host, int port, const std::string& method,
                                   const std::string& host_header, const std::string* origin_header) {
  const auto shown = [](const std::string& text) {
    std::string quoted(1, '\'');
    quoted.append(text, 0, 100);
    return quoted += '\'';
  };
  if (!names_this_server(bound_host, port, host_header))
    return "Host " + shown(host_header) +
           " is not this server (expected 127.0.0.1, localhost or the --host address): a page on another site may be "
           "trying to reach the studio";
  if (method == "GET" || method == "HEAD" || !origin_header) return "";
  const std::string& origin = *origin_header;
  if (origin.starts_with("http://") && names_this_server(bound_host, port, std::string_view(origin).substr(7))) return "";
  return "Origin " + shown(origin) + " is not this server's own page: cross-site requests are refused";
}

struct StudioServer::Impl {
  StudioServerOptions options;
  std::map<std::string, Asset> page;
  StudioSessions sessions;
  std::atomic<uint64_t> revisions{0};
  int port = 0; // once bound
  GuardedServer http{options};

  explicit Impl(StudioServerOptions o) : options(std::move(o)), page(read_page(options.page)), sessions(options.sessions) {
    routes();
  }

  void add_session(httplib::Response& res, StudioSurface surface) {
    const StudioSessions::Added added = sessions.add(std::move(surface));
    send_json(res, 200, surface_json(added.id, *added.session->surface));
  }

  std::string too_large(const httplib::Request& req) const {
    return "upload too large: " + req.get_header_value("Content-Length") + " bytes (this server's --max-upload is " +
           std::to_string(options.max_upload) + " bytes)";
  }

  void routes() {
    http.set_payload_max_length(options.max_upload);
    http.new_task_queue = [threads = size_t(std::max(1, options.threads))] { return new httplib::ThreadPool(threads); };
    // What the Keep-Alive header of each answer says (GuardedServer::serve keeps to it).
    http.set_keep_alive_max_count(keep_alive_requests);
    http.set_keep_alive_timeout(keep_alive_seconds);
    http.set_default_headers({{"X-Content-Type-Options", "nosniff"}, {"Cache-Control", "no-store"}});
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      const std::string origin = req.get_header_value("Origin");
      const std::string refusal = studio_request_refusal(options.host, port, req.method, req.get_header_value("Host"),
                                                         req.has_header("Origin") ? &origin : nullptr);
      if (!refusal.empty()) {
        send_error(res, 403, refusal);
        return httplib::Server::HandlerResponse::Handled;
      }
      // Both would have httplib read a body past --max-upload: chunks are read without
      // the limit, and a gzip or brotli body is inflated without one.
      if (req.has_header("Transfer-Encoding")) {
        send_error(res, 411, "send the body with a Content-Length (Transfer-Encoding is not accepted)");
        return httplib::Server::HandlerResponse::Handled;
      }
      if (req.has_header("Content-Encoding") && req.get_header_value("Content-Encoding") != "identity") {
        send_error(res, 415, "send the body uncompressed (Content-Encoding is not accepted)");
        return httplib::Server::HandlerResponse::Handled;
      }
      return httplib::Server::HandlerResponse::Unhandled;
    });
    // httplib answers 404 and 413 itself, with an empty body; say what happened.
    http.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (!res.body.empty()) return;
      if (res.status == 413)
        send_error(res, 413, too_large(req));
      else if (res.status == 404)
        send_error(res, 404, "no such page or API: " + req.method + " " + req.path.substr(0, 200));
      else if (res.status == 400)
        send_error(res, 400,
                   "malformed request: its request line, headers (at most " + std::to_string(options.max_header) +
                       " bytes) or body could not be read");
      else
        send_error(res, res.status, "request refused (HTTP " + std::to_string(res.status) + ")");
    });

    http.Get("/api/info", [this](const httplib::Request&, httplib::Response& res) {
      send_json(res, 200,
                {{"max_upload", options.max_upload},
                 {"max_faces", options.max_faces},
                 {"max_pixels", options.max_pixels},
                 {"max_result", options.max_result},
                 {"modes", {"curve", "constant-wire", "constant-ribbon", "variable-wire", "variable-ribbon", "duotone", "picture"}},
                 {"formats", {".obj", ".ply", ".stl", ".off", ".glb", ".gltf"}},
                 {"pictures", studio_picture_extensions}});
    });

    http.Get("/api/parameters", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(studio_parameters_json(), "application/json");
    });

    // The body read part by part, keeping only the field `mesh` (httplib would keep every
    // field and then copy the one asked for).
    http.Post("/api/mesh", [this](const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& read) {
      answer(res, [&] {
        const std::string expected = "expected the mesh file or picture as the multipart/form-data field 'mesh'";
        if (!req.is_multipart_form_data()) throw UsageError(expected);
        std::string filename, bytes;
        int meshes = 0;
        bool in_mesh = false;
        const bool read_whole = read(
            [&](const httplib::MultipartFormData& part) {
              in_mesh = part.name == "mesh";
              if (in_mesh) filename = part.filename;
              return !in_mesh || ++meshes == 1;
            },
            [&](const char* data, size_t size) {
              if (in_mesh) bytes.append(data, size);
              return true;
            });
        if (res.status == 413) return send_error(res, 413, too_large(req));
        if (meshes > 1) throw UsageError("more than one field 'mesh': upload one file per request");
        if (!read_whole)
          throw UsageError("malformed multipart/form-data body: no boundary in its Content-Type, bad part headers, or no "
                           "closing boundary");
        if (meshes == 0) throw UsageError(expected);
        add_session(res, load_studio_surface(filename.empty() ? "upload" : filename, bytes, options.max_faces,
                                             options.max_pixels));
      });
    });

    http.Post("/api/demo", [this](const httplib::Request&, httplib::Response& res) {
      answer(res, [&] { add_session(res, demo_surface()); });
    });

    http.Post("/api/make", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, [&] {
        const MakeRequest request = parse_make_request(req.body);
        const auto session = sessions.find(request.session);
        if (!session) return send_error(res, 404, "unknown session (it may have expired): upload the mesh again");
        const int64_t size = studio_result_size(*session->surface, request.params);
        if (size > options.max_result)
          return send_error(res, 413,
                            "this result would hold about " + std::to_string(size) +
                                " curve points, triangles and texture pixels, more than this server's --max-result of " +
                                std::to_string(options.max_result) +
                                ": lower samples, sides, levels, subdivide or texture_size");
        if (request.hold && !options.test_hooks)
          throw UsageError("hold: only for tests of clients (a server started with --test-hooks)");
        // A newer request replaces this one, and a client that went away takes its job with it.
        const int socket = current_socket;
        const std::shared_ptr<Progress> job =
            session->start_job(socket < 0 ? std::function<bool()>() : [socket] { return client_gone(socket); });
        if (request.hold) job->hold();
        struct EndJob {
          StudioSessions::Session& session;
          const std::shared_ptr<Progress>& job;
          ~EndJob() { session.end_job(job); }
        } end_job{*session, job};
        std::lock_guard guard(session->lock);
        auto result = std::make_shared<const StudioResult>(
            make_studio_result(*session->surface, request.params, session->result.get(), job.get()));
        session->result = result;
        json reply = json::parse(studio_stats_json(*result));
        reply["revision"] = ++revisions;
        send_json(res, 200, reply);
      });
    });

    // The job in flight: its stage and the fraction of it done (-1: the stage cannot tell).
    http.Get(R"(/api/progress/([^/]+))", [this](const httplib::Request& req, httplib::Response& res) {
      const auto session = sessions.find(req.matches[1].str());
      if (!session) return send_error(res, 404, "unknown session (it may have expired): upload the mesh again");
      const std::optional<Progress::State> state = session->job_state();
      if (!state) return send_json(res, 200, {{"busy", false}});
      send_json(res, 200, {{"busy", true}, {"stage", state->stage}, {"fraction", state->fraction}});
    });

    // Stops the job in flight, whose request is then answered 409 {"cancelled": true}.
    http.Post(R"(/api/cancel/([^/]+))", [this](const httplib::Request& req, httplib::Response& res) {
      const auto session = sessions.find(req.matches[1].str());
      if (!session) return send_error(res, 404, "unknown session (it may have expired): upload the mesh again");
      send_json(res, 200, {{"cancelled", session->cancel_job()}});
    });

    http.Get(R"(/api/result/([^/]+)/([^/]+))", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, [&] {
        const auto session = sessions.find(req.matches[1].str());
        if (!session) return send_error(res, 404, "unknown session (it may have expired): upload the mesh again");
        const StudioFile file = parse_studio_file(req.matches[2].str());
        std::shared_ptr<const StudioResult> result;
        {
          std::lock_guard guard(session->lock);
          result = session->result;
        }
        if (!result && file != StudioFile::surface)
          return send_error(res, 409, "nothing made yet in this session: POST /api/make first");
        // Both branches lvalues: `result ? *result : StudioResult{}` copied the whole result
        // (mesh, curve, quads) on every download, the view's included.
        const StudioResult nothing;
        const bool seen = file == StudioFile::png || file == StudioFile::svg; // as the view shows it
        const StudioPicture picture = seen ? parse_studio_picture(req.params) : StudioPicture{};
        StudioDownload download = studio_download(*session->surface, result ? *result : nothing, file, picture);
        res.set_header("Content-Disposition", "attachment; filename=\"" + download.filename + "\"");
        // What set_content does, without its copy of a view of tens of megabytes.
        res.body = std::move(download.bytes);
        res.set_header("Content-Type", download.content_type);
      });
    });

    // Last: httplib tries the routes in order, and this pattern would also match /api/...
    http.Get(R"(/(|[A-Za-z0-9_./-]*))", [this](const httplib::Request& req, httplib::Response& res) {
      const std::string path = req.path == "/" ? "/index.html" : req.path;
      const auto it = page.find(path);
      if (it != page.end()) return res.set_content(it->second.bytes, it->second.type);
      if (path == "/index.html")
        return res.set_content("<!doctype html><title>Meander studio</title><p>The studio page is not built: run "
                               "<code>make</code> in the Meander checkout. The JSON API is at /api (docs/studio.md).",
                               "text/html; charset=utf-8");
      send_error(res, 404, "no such page: " + path.substr(0, 200));
    });
  }
};

StudioServer::StudioServer(StudioServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}

StudioServer::~StudioServer() { stop(); }

int StudioServer::bind() {
  const std::string where = impl_->options.host + ":" + std::to_string(impl_->options.port);
  if (impl_->options.port == 0) {
    const int port = impl_->http.bind_to_any_port(impl_->options.host);
    if (port <= 0) throw IOError("cannot listen on " + where);
    impl_->http.lengthen_backlog();
    return impl_->port = port;
  }
  if (!impl_->http.bind_to_port(impl_->options.host, impl_->options.port)) throw IOError("cannot listen on " + where);
  impl_->http.lengthen_backlog();
  return impl_->port = impl_->options.port;
}

void StudioServer::run() { impl_->http.listen_after_bind(); }

void StudioServer::stop() {
  if (impl_->http.is_running()) impl_->http.stop();
}

std::string StudioServer::serve_bytes(std::string_view connection_bytes) {
  ConnectionStream stream(connection_bytes, impl_->options);
  impl_->http.serve(stream);
  return stream.output();
}

} // namespace meander
