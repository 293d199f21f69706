#include "meander/studio_server.h"

#include "meander/error.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <new>
#include <string_view>

namespace meander {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

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
  res.set_content(body.dump(), "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, status, {{"error", message}});
}

// The CLI's exit codes as HTTP: a bad option is the client's request (400), a refused
// file is content the server understood but cannot use (422), anything else is ours.
template <class Work> void answer(httplib::Response& res, Work work) {
  try {
    work();
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
  fs::path scratch;
  std::atomic<uint64_t> downloads{0};
  std::atomic<uint64_t> revisions{0};
  int port = 0; // once bound
  httplib::Server http;

  explicit Impl(StudioServerOptions o) : options(std::move(o)), page(read_page(options.page)), sessions(options.sessions) {
    std::string folder = (fs::temp_directory_path() / "meander-studio-XXXXXX").string();
    if (!mkdtemp(folder.data())) throw IOError(folder + ": cannot make the scratch folder");
    scratch = folder;
    routes();
  }

  ~Impl() {
    std::error_code ignored;
    fs::remove_all(scratch, ignored);
  }

  void add_session(httplib::Response& res, StudioSurface surface) {
    std::string id = sessions.add(std::move(surface));
    const auto session = sessions.find(id);
    send_json(res, 200, surface_json(id, *session->surface));
  }

  void routes() {
    http.set_payload_max_length(options.max_upload);
    http.set_default_headers({{"X-Content-Type-Options", "nosniff"}, {"Cache-Control", "no-store"}});
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      const std::string origin = req.get_header_value("Origin");
      const std::string refusal = studio_request_refusal(options.host, port, req.method, req.get_header_value("Host"),
                                                         req.has_header("Origin") ? &origin : nullptr);
      if (refusal.empty()) return httplib::Server::HandlerResponse::Unhandled;
      send_error(res, 403, refusal);
      return httplib::Server::HandlerResponse::Handled;
    });
    // httplib answers 404 and 413 itself, with an empty body; say what happened.
    http.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (!res.body.empty()) return;
      if (res.status == 413)
        send_error(res, 413, "upload too large: " + req.get_header_value("Content-Length") +
                                 " bytes (this server's --max-upload is " + std::to_string(options.max_upload) +
                                 " bytes)");
      else if (res.status == 404)
        send_error(res, 404, "no such page or API: " + req.method + " " + req.path.substr(0, 200));
      else
        send_error(res, res.status, "request refused (HTTP " + std::to_string(res.status) + ")");
    });

    http.Get("/api/info", [this](const httplib::Request&, httplib::Response& res) {
      send_json(res, 200,
                {{"max_upload", options.max_upload},
                 {"max_faces", options.max_faces},
                 {"max_result", options.max_result},
                 {"modes", {"curve", "constant-wire", "constant-ribbon", "variable-wire", "variable-ribbon", "duotone"}},
                 {"formats", {".obj", ".ply", ".stl", ".off", ".glb", ".gltf"}}});
    });

    http.Post("/api/mesh", [this](const httplib::Request& req, httplib::Response& res) {
      answer(res, [&] {
        if (!req.is_multipart_form_data() || !req.has_file("mesh"))
          throw UsageError("expected the mesh file as the multipart/form-data field 'mesh'");
        const httplib::MultipartFormData file = req.get_file_value("mesh");
        add_session(res, load_studio_surface(file.filename.empty() ? "upload" : file.filename, file.content,
                                             options.max_faces));
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
        std::lock_guard guard(session->lock);
        auto result = std::make_shared<const StudioResult>(make_studio_result(*session->surface, request.params));
        session->result = result;
        json reply = json::parse(studio_stats_json(*result));
        reply["revision"] = ++revisions;
        send_json(res, 200, reply);
      });
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
        const StudioDownload download =
            studio_download(*session->surface, result ? *result : StudioResult{}, file, scratch,
                            "download_" + std::to_string(++downloads));
        res.set_header("Content-Disposition", "attachment; filename=\"" + download.filename + "\"");
        res.set_content(download.bytes, download.content_type);
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
    return impl_->port = port;
  }
  if (!impl_->http.bind_to_port(impl_->options.host, impl_->options.port)) throw IOError("cannot listen on " + where);
  return impl_->port = impl_->options.port;
}

void StudioServer::run() { impl_->http.listen_after_bind(); }

void StudioServer::stop() {
  if (impl_->http.is_running()) impl_->http.stop();
}

} // namespace meander
