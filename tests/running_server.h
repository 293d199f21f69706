// The studio server on a free port of 127.0.0.1, serving from its own thread until
// destroyed (studio_server_test.cpp, studio_http_test.cpp).
#pragma once

#include "meander/studio_server.h"

#include <thread>

namespace meander::test {

struct RunningServer {
  explicit RunningServer(StudioServerOptions options) : server(std::move(options)) {
    port = server.bind();
    thread = std::thread([this] { server.run(); });
  }
  ~RunningServer() {
    server.stop();
    thread.join();
  }
  StudioServer server;
  int port = 0;
  std::thread thread;
};

} // namespace meander::test
