// The studio server on a free port of 127.0.0.1, serving from its own thread until
// destroyed (studio_server_test.cpp, studio_http_test.cpp).
#pragma once

#include "studio_server.h"

#include <httplib.h>

#include <gtest/gtest.h>

#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>
#include <string_view>
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

// A raw TCP connection to 127.0.0.1:port.
class RawConnection {
public:
  explicit RawConnection(int port) : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(uint16_t(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;
  ~RawConnection() { close(fd_); }
  // False once the server has closed or reset the connection.
  bool send(std::string_view bytes) {
    while (!bytes.empty()) {
      const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
      if (n <= 0) return false;
      bytes.remove_prefix(size_t(n));
    }
    return true;
  }
  // Tells the server that nothing more comes.
  void done_sending() { shutdown(fd_, SHUT_WR); }
  // Everything until the server closes.
  std::string receive_all() {
    std::string all;
    char buffer[65536];
    for (;;) {
      pollfd fd{fd_, POLLIN, 0};
      if (poll(&fd, 1, client_wait_seconds * 1000) <= 0) {
        ADD_FAILURE() << "no answer and no close within " << client_wait_seconds << " s";
        return all;
      }
      const ssize_t n = recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) return all;
      all.append(buffer, size_t(n));
    }
  }

private:
  int fd_;
};

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
