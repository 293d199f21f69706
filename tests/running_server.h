// The studio server on a free port of 127.0.0.1, serving from its own thread until
// destroyed (studio_server_test.cpp, studio_http_test.cpp).
#pragma once

#include "studio_server.h"

#include <httplib.h>

#include <thread>

namespace meander::test {

// How long a test's client waits for the server: only to end a test that hangs, never a
// time a busy machine could reach (ctest's timeout, tests/CMakeLists.txt, is longer).
constexpr int client_wait_seconds = 600;

// An HTTP client of 127.0.0.1:port that waits that long to send and to read.
inline httplib::Client client_of(int port) {
  httplib::Client c("127.0.0.1", port);
  c.set_read_timeout(client_wait_seconds);
  c.set_write_timeout(client_wait_seconds);
  return c;
}

// `options` with the timeouts it leaves at their defaults as long as the test's clients
// wait: a busy machine must not decide a test that is not about them.
inline StudioServerOptions patient(StudioServerOptions options) {
  const StudioServerOptions defaults;
  const std::chrono::seconds wait(client_wait_seconds);
  for (auto [timeout, default_value] : {std::pair{&options.idle_timeout, defaults.idle_timeout},
                                        std::pair{&options.header_timeout, defaults.header_timeout},
                                        std::pair{&options.request_timeout, defaults.request_timeout}})
    if (*timeout == default_value) *timeout = wait;
  return options;
}

struct RunningServer {
  explicit RunningServer(StudioServerOptions options) : server(patient(std::move(options))) {
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
