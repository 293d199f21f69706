// `meander serve`: the studio's HTTP server (cpp-httplib), serving the built page and
// the JSON API of docs/studio.md over the work of studio.h. Tests start it on a free
// port and talk to it over real HTTP.
#pragma once

#include "meander/studio.h"

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace meander {

struct StudioServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080; // 0: any free port (bind() tells which)
  // Larger request bodies are refused with 413 and a message before they are read.
  size_t max_upload = size_t(256) << 20;
  // The built page (studio/dist): every file under it is read into memory at start and
  // served under its relative path; requests never reach the file system. A missing
  // folder serves a notice in place of the page (the API still works).
  std::filesystem::path page;
  size_t sessions = 32; // kept at once; the oldest is dropped
  // An upload of more faces is refused (422) before any work (RepairOptions::max_faces).
  int64_t max_faces = 250'000;
  // An uploaded picture of more pixels is refused (422) before it is decoded (a session
  // keeps its picture at 4 bytes a pixel).
  int64_t max_pixels = 16'000'000;
  // A make request whose result would hold more elements (studio_result_size: curve
  // points, triangles, texture pixels) is refused (413) before any work.
  int64_t max_result = 12'000'000;
  // What one connection may send, and how slowly, before it is dropped (a failed read
  // is answered 400 or by closing): the request line and headers together at most
  // max_header bytes within header_timeout of their first byte, the whole request within
  // request_timeout (and the whole answer taken within it), and no wait for the client
  // longer than idle_timeout. A connection carries at most 100 requests and waits 5 s
  // for the next one.
  size_t max_header = size_t(64) << 10;
  std::chrono::milliseconds idle_timeout{5'000};
  std::chrono::milliseconds header_timeout{10'000};
  std::chrono::milliseconds request_timeout{120'000};
  // Connections served at once (more wait for a thread); each holds at most one request
  // body of max_upload bytes, so peak memory is about threads * max_upload plus the work.
  int threads = 16;
  // For tests of clients: a make request may ask its job to wait until cancelled
  // (MakeRequest::hold).
  bool test_hooks = false;
};

// Whether a request may reach the API: its Host must name this server (127.0.0.1,
// localhost or [::1] with or without `port`, or `bound_host` when that is another
// address), so that a web page that rebinds its own DNS name to 127.0.0.1 is refused;
// and a request that changes state (not GET or HEAD) that carries an Origin must come
// from the server's own origin, http://HOST[:port] for such a host, so that another site
// cannot post to it from the user's browser. Returns "" if allowed, else why not.
std::string studio_request_refusal(const std::string& bound_host, int port, const std::string& method,
                                   const std::string& host_header, const std::string* origin_header);

class StudioServer {
public:
  // Reads the page. Throws IOError if it cannot.
  explicit StudioServer(StudioServerOptions options);
  ~StudioServer();
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;

  // Binds the socket; returns the port. Throws IOError("cannot listen on HOST:PORT").
  int bind();
  // Serves until stop() (from another thread or a signal handler's thread).
  void run();
  void stop();

  // Answers the raw bytes of a connection (one or more requests, keep-alive included)
  // as the server answers a socket, with the same limits, and returns what it writes
  // back; nothing touches the network. For the HTTP fuzz target and tests.
  std::string serve_bytes(std::string_view connection_bytes);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace meander
