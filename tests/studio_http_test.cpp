// The studio's HTTP layer against what a network can send (issue 7, item 6): malformed
// multipart bodies, huge headers, slow and stalled clients, path traversal in every
// parameter, request smuggling, 100 concurrent uploads; the server answers 4xx or closes
// the connection, stays up, and the heap it holds stays bounded (heap_peak.h). Exact byte sequences go through
// StudioServer::serve_bytes (the server's own connection code, from memory); connection
// behaviour and memory through real sockets on a free port of 127.0.0.1.
#include "studio_server.h"
#include "heap_peak.h"
#include "running_server.h"
#include "test_support.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <fstream>
#include <regex>
#include <thread>

namespace meander {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using test::RunningServer;

// The status codes of the answers in `bytes`, in order.
std::vector<int> statuses(const std::string& bytes) {
  std::vector<int> codes;
  static const std::regex status_line(R"(HTTP/1\.1 (\d{3}) )");
  for (auto it = std::sregex_iterator(bytes.begin(), bytes.end(), status_line); it != std::sregex_iterator(); ++it)
    codes.push_back(std::stoi((*it)[1]));
  return codes;
}

// The error message of the first answer in `bytes`.
std::string error_of(const std::string& bytes) {
  std::smatch m;
  static const std::regex answer(R"(\r\nContent-Length: (\d+)\r\n[^]*?\r\n\r\n)");
  if (!std::regex_search(bytes, m, answer)) return "";
  const json body = json::parse(bytes.substr(size_t(m.position(0) + m.length(0)), std::stoul(m[1])), nullptr, false);
  return body.is_object() ? body.value("error", "") : "";
}

std::string post(const std::string& path, const std::string& type, const std::string& body,
                 const std::string& more_headers = "") {
  return "POST " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: " + type +
         "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n" + more_headers + "\r\n" + body;
}

std::string get(const std::string& path) { return "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"; }

const std::string tetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";

std::string part(const std::string& name, const std::string& filename, const std::string& content) {
  return "--b0undary\r\nContent-Disposition: form-data; name=\"" + name + "\"; filename=\"" + filename +
         "\"\r\nContent-Type: application/octet-stream\r\n\r\n" + content + "\r\n";
}

const std::string multipart = "multipart/form-data; boundary=b0undary";

StudioServerOptions small_limits() { return {.port = 0, .max_upload = 1 << 20}; }

TEST(StudioHttp, MalformedMultipartBodiesAreRefusedWithAMessage) {
  StudioServer server(small_limits());
  const std::string good = part("mesh", "t.obj", tetrahedron) + "--b0undary--\r\n";
  ASSERT_EQ(statuses(server.serve_bytes(post("/api/mesh", multipart, good))), std::vector<int>{200});

  const std::string malformed = "malformed multipart/form-data body: no boundary in its Content-Type, bad part headers, "
                                "or no closing boundary";
  const std::string expected = "expected the mesh file or picture as the multipart/form-data field 'mesh'";
  const std::string binary("\x00\xff\x1f\x8b\r\n--\r\n\x00--b0undary\x00", 22);
  const struct {
    const char* what;
    std::string request;
    std::string error;
    size_t answers = 1;
  } cases[] = {
      {"no boundary", post("/api/mesh", "multipart/form-data", good), malformed},
      {"empty boundary", post("/api/mesh", "multipart/form-data; boundary=", good), malformed},
      {"truncated body", post("/api/mesh", multipart, good.substr(0, good.size() / 2)), malformed},
      {"no closing boundary", post("/api/mesh", multipart, part("mesh", "t.obj", tetrahedron)), malformed},
      {"Content-Length longer than the body",
       "POST /api/mesh HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: " + multipart + "\r\nContent-Length: " +
           std::to_string(good.size() + 100) + "\r\n\r\n" + good,
       malformed},
      {"Content-Length shorter than the body",
       "POST /api/mesh HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: " + multipart + "\r\nContent-Length: " +
           std::to_string(good.size() - 20) + "\r\n\r\n" + good,
       malformed, 2},
      {"field not named mesh", post("/api/mesh", multipart, part("file", "t.obj", tetrahedron) + "--b0undary--\r\n"),
       expected},
      {"two mesh fields",
       post("/api/mesh", multipart, part("mesh", "a.obj", tetrahedron) + part("mesh", "b.obj", tetrahedron) + "--b0undary--\r\n"),
       "more than one field 'mesh': upload one file per request"},
      {"binary garbage", post("/api/mesh", multipart, binary), malformed},
      {"binary garbage, no multipart", post("/api/mesh", "application/octet-stream", binary), expected},
      {"part header line of 20 000 bytes",
       post("/api/mesh", multipart,
            "--b0undary\r\nContent-Disposition: form-data; name=\"mesh\"; filename=\"" + std::string(20000, 'a') +
                ".obj\"\r\n\r\n" + tetrahedron + "\r\n--b0undary--\r\n"),
       malformed},
      {"a part without headers", post("/api/mesh", multipart, "--b0undary\r\n\r\n" + tetrahedron + "\r\n--b0undary--\r\n"),
       expected},
  };
  for (const auto& c : cases) {
    const std::string answer = server.serve_bytes(c.request);
    // What follows a request not read to its end is never taken as another; what
    // follows a body shorter than the parts is the next request (here a bad one).
    EXPECT_EQ(statuses(answer), std::vector<int>(c.answers, 400)) << c.what << "\n" << answer;
    EXPECT_EQ(error_of(answer), c.error) << c.what;
  }
  // The file name of a mesh that is not a mesh: the reader's message (422).
  const std::string not_a_mesh = server.serve_bytes(
      post("/api/mesh", multipart, part("mesh", "garbage.obj", binary) + "--b0undary--\r\n"));
  EXPECT_EQ(statuses(not_a_mesh), std::vector<int>{422}) << not_a_mesh;
  EXPECT_EQ(error_of(not_a_mesh).rfind("garbage.obj", 0), 0u) << not_a_mesh;
}

TEST(StudioHttp, BodiesThatWouldPassTheUploadLimitAreRefusedBeforeReading) {
  StudioServer server(small_limits());
  const std::string json_type = "application/json";
  // httplib reads chunks without the payload limit and inflates gzip without one.
  const std::string chunked = server.serve_bytes("POST /api/make HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: "
                                                 "chunked\r\n\r\n100000\r\n" + std::string(4096, 'a'));
  EXPECT_EQ(statuses(chunked), std::vector<int>{411});
  EXPECT_EQ(error_of(chunked), "send the body with a Content-Length (Transfer-Encoding is not accepted)");
  const std::string gzip = server.serve_bytes(post("/api/make", json_type, "\x1f\x8b\x08", "Content-Encoding: gzip\r\n"));
  EXPECT_EQ(statuses(gzip), std::vector<int>{415});
  EXPECT_EQ(error_of(gzip), "send the body uncompressed (Content-Encoding is not accepted)");
  // A length over --max-upload: 413 at once, nothing of the body read, nothing after it run.
  const std::string huge = server.serve_bytes("POST /api/mesh HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: " + multipart +
                                              "\r\nContent-Length: 1000000000000\r\n\r\n" + get("/api/info"));
  EXPECT_EQ(statuses(huge), std::vector<int>{413});
  EXPECT_EQ(error_of(huge), "upload too large: 1000000000000 bytes (this server's --max-upload is 1048576 bytes)");
  // A POST without a length has no body (httplib would wait for the client to close).
  const std::string no_length = server.serve_bytes("POST /api/demo HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n" + get("/api/info"));
  EXPECT_EQ(statuses(no_length), (std::vector<int>{200, 200}));
}

// A refused request's body, or a GET's, is not read; it used to be run as the next
// request of the connection, which passed the Origin check a cross-site page had failed.
TEST(StudioHttp, AnUnreadBodyIsNeverRunAsARequest) {
  StudioServer server(small_limits());
  const std::string smuggled = post("/api/demo", "text/plain", "");
  for (const std::string& request :
       {post("/api/demo", "text/plain", smuggled, "Origin: http://evil.example\r\n"),
        post("/api/demo", "text/plain", std::string(5000, 'x') + smuggled, "Origin: http://evil.example\r\n"),
        "GET /api/info HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: " + std::to_string(smuggled.size()) + "\r\n\r\n" + smuggled,
        "GET /api/info HTTP/1.1\r\nHost: evil.example\r\nContent-Length: " + std::to_string(smuggled.size()) + "\r\n\r\n" + smuggled}) {
    EXPECT_EQ(statuses(server.serve_bytes(request)).size(), 1u) << request;
  }
  // Requests read to their end keep the connection for the next (keep-alive).
  EXPECT_EQ(statuses(server.serve_bytes(get("/api/info") + post("/api/demo", "text/plain", "") + get("/api/info"))),
            (std::vector<int>{200, 200, 200}));
}

// Found by fuzz_studio_http: a message quoting bytes that are not UTF-8 made the JSON
// writer throw, and from httplib's error handler (404) that ended the process.
TEST(StudioHttp, BytesThatAreNotUtf8InAMessageLeaveTheServerUp) {
  RunningServer running(small_limits());
  for (const std::string& request :
       std::vector<std::string>{get("/%FC%FF"), get("/api/result/%FC/result.stl"), "PO\xfcST / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n",
        post("/api/mesh", multipart, part("mesh", "\xfc\xfe.obj", "v 1 2\n") + "--b0undary--\r\n")}) {
    test::RawConnection c(running.port);
    c.send(request);
    c.done_sending();
    const std::string answer = c.receive_all();
    const std::vector<int> codes = statuses(answer);
    ASSERT_EQ(codes.size(), 1u) << request;
    EXPECT_GE(codes[0], 400) << request;
    EXPECT_LT(codes[0], 500) << request;
  }
  // The message quotes the path with U+FFFD for each byte that is not UTF-8.
  EXPECT_EQ(error_of(running.server.serve_bytes(get("/%FC%FF"))), "no such page or API: GET /\xef\xbf\xbd\xef\xbf\xbd");
  test::RawConnection next(running.port);
  next.send("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(statuses(next.receive_all()), std::vector<int>{200});
}

TEST(StudioHttp, ManyRangesDoNotMultiplyTheAnswer) {
  const fs::path page = test::output_dir() / "page";
  fs::create_directories(page);
  const std::string html = "<!doctype html>" + std::string(10000, ' ');
  std::ofstream(page / "index.html") << html;
  StudioServer server({.port = 0, .page = page});
  std::string ranges;
  for (int i = 0; i < 2000; ++i) ranges += (i ? ",0-" : "0-");
  const std::string answer =
      server.serve_bytes("GET /index.html HTTP/1.1\r\nHost: 127.0.0.1\r\nRange: bytes=" + ranges + "\r\n\r\n");
  EXPECT_EQ(statuses(answer), std::vector<int>{200});
  EXPECT_LT(answer.size(), html.size() + 1000);
}

TEST(StudioHttp, HugeHeadersAreCutOffAndTheServerAnswersTheNext) {
  RunningServer running(small_limits());
  const std::string line(size_t(1) << 20, 'a');
  std::string many;
  for (int i = 0; i < 10000; ++i) many += "X-Header-" + std::to_string(i) + ": " + std::to_string(i) + "\r\n";
  std::string millions;
  for (int i = 0; i < 2'500'000; ++i) millions += "X: y\r\n";
  const std::vector<std::string> requests = {"GET /" + line + " HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n",
                                     "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Long: " + line + "\r\n\r\n",
                                     "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n" + many + "\r\n",
                                     "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n" + millions + "\r\n",
                                     "GET / HTTP/1.1\n" + many + "\n", std::string(size_t(4) << 20, '\n')};
  const size_t start = test::reset_heap_peak();
  for (const std::string& request : requests) {
    test::RawConnection c(running.port);
    c.send(request);
    c.done_sending();
    const std::string answer = c.receive_all();
    // Refused (400) or closed without an answer, never served.
    for (const int code : statuses(answer)) EXPECT_EQ(code, 400) << request.substr(0, 40);
    if (!answer.empty()) {
      EXPECT_EQ(error_of(answer),
                "malformed request: its request line, headers (at most 65536 bytes) or body could not be read");
    }
    test::RawConnection next(running.port);
    next.send("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(statuses(next.receive_all()), std::vector<int>{200});
  }
  // About 20 MB were sent; httplib alone kept every header (2.5 million of them took
  // some 250 MB) and every byte of a line until its end.
  EXPECT_LT(test::heap_peak() - start, size_t(16) << 20) << "bytes";
}

TEST(StudioHttp, SlowAndStalledClientsAreDroppedWithoutBlockingOthers) {
  // Four threads for eight slow clients: the others are answered once they are dropped.
  StudioServerOptions options = small_limits();
  options.threads = 4;
  options.idle_timeout = std::chrono::milliseconds(250);
  options.header_timeout = std::chrono::milliseconds(500);
  options.request_timeout = std::chrono::milliseconds(1000);
  RunningServer running(options);
  std::vector<std::unique_ptr<test::RawConnection>> slow;
  for (int i = 0; i < 8; ++i) slow.push_back(std::make_unique<test::RawConnection>(running.port));
  // Two stall: one in its headers, one in its body.
  test::RawConnection stalled_headers(running.port), stalled_body(running.port);
  stalled_headers.send("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Wait: ");
  stalled_body.send("POST /api/make HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 100\r\n\r\n{\"session\":");
  // The others send a byte every 100 ms until the server closes them (or for 60 s, to
  // detect a hang: a byte within each read's wait used to hold a thread for ever).
  std::atomic<int> open{8};
  std::thread trickle([&] {
    const std::string request = "GET /api/info HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: " + std::string(600, 'a');
    std::vector<bool> alive(slow.size(), true);
    for (size_t k = 0; k < request.size() && open > 0; ++k) {
      for (size_t i = 0; i < slow.size(); ++i)
        if (alive[i] && !slow[i]->send(request.substr(k, 1))) alive[i] = false, --open;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  for (int i = 0; i < 4; ++i) {
    test::RawConnection c(running.port);
    c.send("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(statuses(c.receive_all()), std::vector<int>{200});
  }
  // Every slow or stalled connection ends, answered 400 or closed.
  for (test::RawConnection* c : {&stalled_headers, &stalled_body})
    for (const int code : statuses(c->receive_all())) EXPECT_EQ(code, 400);
  for (auto& c : slow)
    for (const int code : statuses(c->receive_all())) EXPECT_EQ(code, 400);
  trickle.join();
}

TEST(StudioHttp, PathTraversalInEveryParameterFindsNothingOutside) {
  // A page folder, and beside it a file no request may reach.
  const fs::path folder = test::output_dir();
  fs::create_directories(folder / "page" / "assets");
  std::ofstream(folder / "page" / "index.html") << "<!doctype html>page";
  std::ofstream(folder / "page" / "assets" / "app.js") << "app";
  std::ofstream(folder / "secret.txt") << "SECRET-CANARY";
  const std::string absolute = (folder / "secret.txt").string();
  StudioServer server({.port = 0, .max_upload = 1 << 20, .page = folder / "page"});
  const std::string demo = server.serve_bytes(post("/api/demo", "text/plain", ""));
  const std::string session = json::parse(demo.substr(demo.find("\r\n\r\n") + 4))["session"];
  ASSERT_EQ(statuses(server.serve_bytes(post("/api/make", "application/json", json{{"session", session}}.dump()))),
            std::vector<int>{200});
  ASSERT_EQ(statuses(server.serve_bytes(get("/api/result/" + session + "/curve.svg"))), std::vector<int>{200});
  ASSERT_EQ(statuses(server.serve_bytes(get("/assets/app.js"))), std::vector<int>{200});

  const std::vector<std::string> hostile = {"../secret.txt", "..%2fsecret.txt", "%2e%2e%2fsecret.txt", "%2e%2e/secret.txt",
                                            "..\\secret.txt", "..%5csecret.txt", "....//secret.txt", absolute,
                                            "%2F" + absolute.substr(1), "secret.txt%00.png", "result.stl%00", "%00",
                                            "..", ".", "%2e%2e", std::string(3000, '.') + "/secret.txt"};
  std::vector<std::string> paths;
  for (const std::string& h : hostile) {
    paths.push_back("/" + h);                                  // static files
    paths.push_back("/assets/../" + h);                        // ... under a folder
    paths.push_back("/api/result/" + session + "/" + h);       // the file name
    paths.push_back("/api/result/" + h + "/result.stl");       // the session
    paths.push_back("/api/result/" + session + "/../../" + h); // both
  }
  for (const std::string& path : paths) {
    const std::string answer = server.serve_bytes(get(path));
    const std::vector<int> codes = statuses(answer);
    ASSERT_EQ(codes.size(), 1u) << path;
    EXPECT_TRUE(codes[0] == 400 || codes[0] == 404) << path << ": " << codes[0];
    EXPECT_EQ(answer.find("SECRET-CANARY"), std::string::npos) << path;
  }
  // The JSON parameters: a session is a key, never a path.
  for (const std::string& h : hostile) {
    const std::string answer = server.serve_bytes(post("/api/make", "application/json", json{{"session", h}}.dump()));
    EXPECT_EQ(statuses(answer), std::vector<int>{404}) << h;
  }
  // An upload's file name only names the file in messages: nothing is written there.
  for (const std::string& name : std::vector<std::string>{"../../escaped.obj", absolute + ".obj", std::string("a\0b.obj", 7), "..\\escaped.obj"}) {
    const std::string answer = server.serve_bytes(post("/api/mesh", multipart, part("mesh", name, tetrahedron) + "--b0undary--\r\n"));
    EXPECT_EQ(statuses(answer), std::vector<int>{200}) << answer;
  }
  EXPECT_FALSE(fs::exists(folder / "escaped.obj"));
  EXPECT_FALSE(fs::exists(absolute + ".obj"));
  EXPECT_EQ(test::read_file(folder / "secret.txt"), "SECRET-CANARY");
}

TEST(StudioHttp, HundredConcurrentUploadsSucceedInBoundedMemory) {
  const fs::path demo = test::output_dir() / "pretzel.obj";
  ASSERT_EQ(test::run_cli({"generate", "pretzel", "--faces", "1600", "-o", demo.string()}).exit_code, 0);
  const std::string bytes = test::read_file(demo);
  RunningServer running({.port = 0});
  const size_t start = test::reset_heap_peak();
  std::atomic<int> ok{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < 100; ++i)
    threads.emplace_back([&] {
      httplib::Client c = test::client_of(running.port);
      const auto res = c.Post("/api/mesh", httplib::MultipartFormDataItems{{"mesh", bytes, "pretzel.obj", ""}});
      if (res && res->status == 200 && json::parse(res->body)["faces"] == 1600) ++ok;
      else ADD_FAILURE() << httplib::to_string(res.error()) << " " << (res ? res->body : "");
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(ok.load(), 100);
  // 100 uploads of about 60 KB: the clients' copies, 16 at a time in the server, 32
  // sessions kept. Generous: 64 MB and ten times every upload at once.
  const size_t grown = test::heap_peak() - start;
  EXPECT_LT(grown, (size_t(64) << 20) + 10 * 100 * bytes.size()) << "bytes for uploads of " << bytes.size() << " bytes";
  std::printf("100 concurrent uploads of %zu bytes: the heap's peak grew by %zu KiB\n", bytes.size(), grown >> 10);
  test::RawConnection next(running.port);
  next.send("GET /api/info HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(statuses(next.receive_all()), std::vector<int>{200});
}

} // namespace
} // namespace meander
