// `meander serve` over real HTTP: the server on a free port of 127.0.0.1, httplib's client.
#include "meander/studio_server.h"
#include "test_support.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <thread>

namespace meander {
namespace {

using nlohmann::json;

class StudioServerTest : public ::testing::Test {
protected:
  void SetUp() override {
    server_ = std::make_unique<StudioServer>(StudioServerOptions{.port = 0, .max_upload = 1 << 20});
    port_ = server_->bind();
    thread_ = std::thread([this] { server_->run(); });
  }
  void TearDown() override {
    server_->stop();
    thread_.join();
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(120);
    return c;
  }
  std::string demo_session() {
    const auto res = client().Post("/api/demo", "", "application/json");
    EXPECT_TRUE(res && res->status == 200);
    return json::parse(res->body)["session"];
  }
  static std::string error_of(const httplib::Result& res) { return json::parse(res->body).value("error", ""); }

  std::unique_ptr<StudioServer> server_;
  int port_ = 0;
  std::thread thread_;
};

TEST_F(StudioServerTest, RoundTripOnTheDemoModel) {
  const std::string session = demo_session();
  EXPECT_EQ(session.size(), 32u);
  auto c = client();
  const auto made = c.Post("/api/make", json{{"session", session}, {"mode", "variable-wire"}, {"s", 0.4}, {"levels", 0}}.dump(),
                           "application/json");
  ASSERT_TRUE(made);
  ASSERT_EQ(made->status, 200) << made->body;
  const json stats = json::parse(made->body);
  EXPECT_EQ(stats["mode"], "variable-wire");
  EXPECT_EQ(stats["watertight"], true);
  EXPECT_EQ(stats["self_intersecting"], false);
  const auto stl = c.Get("/api/result/" + session + "/result.stl");
  ASSERT_TRUE(stl);
  ASSERT_EQ(stl->status, 200);
  EXPECT_EQ(stl->get_header_value("Content-Type"), "model/stl");
  uint32_t triangles = 0;
  std::memcpy(&triangles, stl->body.data() + 80, 4);
  EXPECT_EQ(triangles, stats["triangles"].get<uint32_t>());
  EXPECT_EQ(stl->body.size(), 84 + 50 * size_t(triangles));
  for (const char* file : {"result.3mf", "result.glb", "result.zip", "curve.svg", "view.bin", "surface.bin"}) {
    const auto res = c.Get("/api/result/" + session + "/" + file);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200) << file << ": " << res->body;
    EXPECT_GT(res->body.size(), 16u) << file;
  }
}

TEST_F(StudioServerTest, UploadOfAMeshFile) {
  httplib::MultipartFormDataItems items = {
      {"mesh", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "square.obj", "text/plain"}};
  const auto res = client().Post("/api/mesh", items);
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(json::parse(res->body)["faces"], 1);
  EXPECT_EQ(json::parse(res->body)["name"], "square.obj");
}

TEST_F(StudioServerTest, MalformedUploadsAreRefusedWithTheCliMessage) {
  auto c = client();
  const auto bad = c.Post("/api/mesh", httplib::MultipartFormDataItems{{"mesh", "v 0 0 0\nf 1 2 3\n", "bad.obj", ""}});
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 422);
  EXPECT_EQ(error_of(bad).rfind("bad.obj:2: ", 0), 0u) << bad->body;
  const auto no_field = c.Post("/api/mesh", httplib::MultipartFormDataItems{{"file", "x", "a.obj", ""}});
  ASSERT_TRUE(no_field);
  EXPECT_EQ(no_field->status, 400);
  EXPECT_EQ(error_of(no_field), "expected the mesh file as the multipart/form-data field 'mesh'");
  const auto not_multipart = c.Post("/api/mesh", "v 0 0 0", "text/plain");
  ASSERT_TRUE(not_multipart);
  EXPECT_EQ(not_multipart->status, 400);
  const auto bad_json = c.Post("/api/make", "{\"session\":", "application/json");
  ASSERT_TRUE(bad_json);
  EXPECT_EQ(bad_json->status, 400);
  EXPECT_EQ(error_of(bad_json), "request body is not valid JSON");
  // The server is still there.
  EXPECT_EQ(demo_session().size(), 32u);
}

TEST_F(StudioServerTest, OversizedUploadGets413WithAMessage) {
  const std::string big(size_t(1 << 20) + 1000, 'v');
  const auto res = client().Post("/api/mesh", httplib::MultipartFormDataItems{{"mesh", big, "big.obj", ""}});
  ASSERT_TRUE(res) << httplib::to_string(res.error());
  EXPECT_EQ(res->status, 413);
  EXPECT_NE(error_of(res).find("--max-upload is 1048576 bytes"), std::string::npos) << res->body;
}

TEST_F(StudioServerTest, PathTraversalFails) {
  const std::string session = demo_session();
  auto c = client();
  ASSERT_EQ(c.Post("/api/make", json{{"session", session}}.dump(), "application/json")->status, 200);
  for (const std::string& path : std::vector<std::string>{"/../../../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/assets/../../CMakeLists.txt",
        "/api/result/" + session + "/..%2f..%2f..%2fetc%2fpasswd", "/api/result/" + session + "/../../etc/passwd",
        "/api/result/..%2f" + session + "/result.stl", "/api/result/" + session + "/%2fetc%2fpasswd",
        "/api/result/" + session + "/result.stl%00.png"}) {
    const auto res = c.Get(path);
    ASSERT_TRUE(res) << path;
    EXPECT_GE(res->status, 400) << path;
    EXPECT_LT(res->status, 500) << path;
    EXPECT_EQ(res->body.find("root:"), std::string::npos) << path;
  }
  // A file name in an upload is a name for messages, never a path.
  const auto upload = c.Post("/api/mesh", httplib::MultipartFormDataItems{
                                             {"mesh", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "../../../tmp/x.obj", ""}});
  ASSERT_TRUE(upload);
  EXPECT_EQ(json::parse(upload->body)["name"], "x.obj");
}

TEST_F(StudioServerTest, TwentyConcurrentRequestsSucceed) {
  const std::string session = demo_session();
  std::atomic<int> ok{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < 20; ++i)
    threads.emplace_back([&, i] {
      auto c = client();
      // A mix: new sessions, makes on one shared session with different seeds, downloads.
      httplib::Result res = i % 3 == 0 ? c.Post("/api/demo", "", "application/json")
                            : i % 3 == 1
                                ? c.Post("/api/make", json{{"session", session}, {"seed", i}, {"mode", "constant-ribbon"}}.dump(),
                                         "application/json")
                                : c.Post("/api/make", json{{"session", session}, {"seed", i}}.dump(), "application/json");
      if (res && res->status == 200) ++ok;
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(ok.load(), 20);
  const auto view = client().Get("/api/result/" + session + "/view.bin");
  ASSERT_TRUE(view);
  EXPECT_EQ(view->status, 200);
  EXPECT_EQ(view->body.substr(0, 4), "MNDR");
}

} // namespace
} // namespace meander
