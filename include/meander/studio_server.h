// `meander serve`: the studio's HTTP server (cpp-httplib), serving the built page and
// the JSON API of docs/studio.md over the work of studio.h. Tests start it on a free
// port and talk to it over real HTTP.
#pragma once

#include "meander/studio.h"

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

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
};

class StudioServer {
public:
  // Reads the page and makes a private scratch folder (mode 0700, removed by the
  // destructor) for the files the writers produce. Throws IOError if it cannot.
  explicit StudioServer(StudioServerOptions options);
  ~StudioServer();
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;

  // Binds the socket; returns the port. Throws IOError("cannot listen on HOST:PORT").
  int bind();
  // Serves until stop() (from another thread or a signal handler's thread).
  void run();
  void stop();

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace meander
