// `meander serve` over real HTTP: the server on a free port of 127.0.0.1, httplib's client.
#include "meander/io.h"
#include "studio_server.h"
#include "running_server.h"
#include "test_support.h"
#include "view_decoder.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <thread>

namespace meander {
namespace {

using nlohmann::json;

using test::RunningServer;

class StudioServerTest : public ::testing::Test {
protected:
  void SetUp() override {
    running_ = std::make_unique<RunningServer>(StudioServerOptions{.port = 0, .max_upload = 1 << 20});
    port_ = running_->port;
  }
  void TearDown() override { running_.reset(); }
  httplib::Client client() const { return test::client_of(port_); }
  std::string demo_session() {
    const auto res = client().Post("/api/demo", "", "application/json");
    EXPECT_TRUE(res && res->status == 200);
    return json::parse(res->body)["session"];
  }
  static std::string error_of(const httplib::Result& res) { return json::parse(res->body).value("error", ""); }

  std::unique_ptr<RunningServer> running_;
  int port_ = 0;
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

// A script may save a preview as it saves a full result (the page waits for the full one).
TEST_F(StudioServerTest, APreviewDownloadsLikeAFullResultUnderItsOwnName) {
  const std::string session = demo_session();
  auto c = client();
  const auto made = c.Post("/api/make", json{{"session", session}, {"mode", "variable-wire"}, {"preview", true}}.dump(),
                           "application/json");
  ASSERT_TRUE(made);
  ASSERT_EQ(made->status, 200) << made->body;
  const json stats = json::parse(made->body);
  ASSERT_EQ(stats["preview"], true);
  const auto stl = c.Get("/api/result/" + session + "/result.stl");
  ASSERT_TRUE(stl);
  ASSERT_EQ(stl->status, 200) << stl->body;
  uint32_t triangles = 0;
  std::memcpy(&triangles, stl->body.data() + 80, 4);
  EXPECT_EQ(triangles, stats["triangles"].get<uint32_t>());
  EXPECT_EQ(stl->body.size(), 84 + 50 * size_t(triangles));
  EXPECT_EQ(stl->get_header_value("Content-Disposition"), "attachment; filename=\"pretzel_variable-wire_preview.stl\"");
  for (const char* file : {"result.3mf", "result.glb", "result.zip", "curve.svg"}) {
    const auto res = c.Get("/api/result/" + session + "/" + file);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200) << file << ": " << res->body;
    EXPECT_NE(res->get_header_value("Content-Disposition").find("_preview."), std::string::npos) << file;
  }
  // The full result that follows takes the plain name.
  ASSERT_EQ(c.Post("/api/make", json{{"session", session}, {"mode", "variable-wire"}, {"levels", 0}}.dump(), "application/json")->status,
            200);
  EXPECT_EQ(c.Get("/api/result/" + session + "/result.stl")->get_header_value("Content-Disposition"),
            "attachment; filename=\"pretzel_variable-wire.stl\"");
}

// What the page's parseView (studio/src/main.js) reads from view.bin, checked array by
// array: the sizes add up, the indices are in range, a mesh has unit normals and no loop
// in the page has to compute anything.
// The view decoded as the page decodes it, checked: positions in the header's box, unit
// normals where there are faces, indices within the vertices.
test::DecodedView check_view(const std::string& bytes, const std::string& what) {
  test::DecodedView view = test::decode_view(bytes);
  if (!view.ok) return view;
  const bool faces = view.triangles > 0;
  EXPECT_EQ(view.flags & 2 ? 1 : 0, faces ? 1 : 0) << what << ": a mesh comes with its normals";
  const float step = std::max({view.box[3] - view.box[0], view.box[4] - view.box[1], view.box[5] - view.box[2]}) / 65535;
  for (size_t i = 0; i < view.vertices; ++i)
    for (size_t k = 0; k < 3; ++k)
      if (!(view.positions[3 * i + k] >= view.box[k] - step && view.positions[3 * i + k] <= view.box[3 + k] + step)) {
        ADD_FAILURE() << what << ": vertex " << i << " outside the header's bounding box";
        return view;
      }
  for (size_t i = 0; faces && i < view.vertices; ++i) {
    const int8_t* n = view.normals.data() + 4 * i;
    const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    if (std::abs(length - 127) > 2) {
      ADD_FAILURE() << what << ": normal " << i << " has length " << length << " (127 expected)";
      return view;
    }
  }
  for (const std::vector<uint32_t>* indices : {&view.triangle_indices, &view.segment_indices})
    for (size_t i = 0; i < indices->size(); ++i)
      if ((*indices)[i] >= view.vertices) {
        ADD_FAILURE() << what << ": index " << i << " is " << (*indices)[i] << ", past the " << view.vertices << " vertices";
        return view;
      }
  return view;
}

// Every mode's preview, and its full result, come to the page as the geometry the stats
// count: the triangles (or the curve's segments), with normals, and texture coordinates
// for duotone.
TEST_F(StudioServerTest, TheViewOfEveryPreviewIsWhatThePageReads) {
  const std::string session = demo_session();
  auto c = client();
  const auto surface = c.Get("/api/result/" + session + "/surface.bin");
  ASSERT_TRUE(surface);
  const test::DecodedView drawn = check_view(surface->body, "surface.bin");
  EXPECT_EQ(drawn.triangles, 1600u); // the pretzel's triangles
  for (const char* mode : {"curve", "constant-wire", "constant-ribbon", "variable-wire", "variable-ribbon", "duotone"})
    for (const bool preview : {true, false}) {
      const std::string what = std::string(mode) + (preview ? " preview" : " full");
      const auto made = c.Post("/api/make", json{{"session", session}, {"mode", mode}, {"levels", 1}, {"preview", preview}}.dump(),
                               "application/json");
      ASSERT_TRUE(made);
      ASSERT_EQ(made->status, 200) << what << ": " << made->body;
      const json stats = json::parse(made->body);
      EXPECT_EQ(stats["preview"], preview) << what;
      const auto bytes = c.Get("/api/result/" + session + "/view.bin");
      ASSERT_TRUE(bytes);
      ASSERT_EQ(bytes->status, 200) << what;
      const test::DecodedView view = check_view(bytes->body, what);
      if (std::string(mode) == "curve") {
        EXPECT_EQ(view.triangles, 0u) << what;
        EXPECT_EQ(view.segments, stats["curve_points"].get<uint32_t>()) << what << ": one closed curve";
        EXPECT_EQ(view.flags, 0u) << what;
      } else {
        EXPECT_EQ(view.triangles, stats["triangles"].get<uint32_t>()) << what;
        EXPECT_EQ(view.segments, 0u) << what;
        EXPECT_EQ(view.flags, std::string(mode) == "duotone" ? 3u : 2u) << what;
      }
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

// A picture uploaded as a mesh is: the session is a picture, picture mode draws it, and
// its drawing downloads as SVG with one closed path.
TEST_F(StudioServerTest, APictureUploadIsDrawnWithOneLine) {
  const auto info = client().Get("/api/info");
  ASSERT_TRUE(info);
  const json about = json::parse(info->body);
  EXPECT_NE(std::find(about["pictures"].begin(), about["pictures"].end(), ".jpg"), about["pictures"].end());
  EXPECT_NE(std::find(about["modes"].begin(), about["modes"].end(), "picture"), about["modes"].end());
  Image image{.width = 64, .height = 48};
  for (int32_t i = 0; i < 64 * 48; ++i) {
    const uint8_t g = uint8_t(4 * (i % 64)); // dark on the left
    image.rgba.insert(image.rgba.end(), {g, g, g, 255});
  }
  const auto res = client().Post("/api/mesh", httplib::MultipartFormDataItems{{"mesh", png_file_bytes(image), "ramp.png", "image/png"}});
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const json reply = json::parse(res->body);
  EXPECT_EQ(reply["picture"], json({{"width", 64}, {"height", 48}}));
  const std::string session = reply["session"];
  const auto made = client().Post("/api/make", json{{"session", session}, {"mode", "picture"}, {"paper", "A5"}}.dump(), "application/json");
  ASSERT_TRUE(made);
  ASSERT_EQ(made->status, 200) << made->body;
  EXPECT_EQ(json::parse(made->body)["curves"], 1);
  const auto svg = client().Get("/api/result/" + session + "/curve.svg?size=800x600");
  ASSERT_TRUE(svg);
  ASSERT_EQ(svg->status, 200) << svg->body;
  EXPECT_EQ(svg->get_header_value("Content-Type"), "image/svg+xml");
  int layers = 0;
  const std::vector<test::SvgPath> paths = test::read_svg_paths(svg->body, layers);
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_TRUE(paths[0].closed);
  const auto wrong = client().Post("/api/make", json{{"session", session}, {"mode", "curve"}}.dump(), "application/json");
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 400);
  EXPECT_EQ(error_of(wrong), "ramp.png: a picture: only picture mode draws it (open a mesh for the other modes)");
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
  EXPECT_EQ(error_of(no_field), "expected the mesh file or picture as the multipart/form-data field 'mesh'");
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

// Makes on one session replace each other: each is made or answered 409 cancelled, and
// the last one begun is made.
TEST_F(StudioServerTest, TwentyConcurrentRequestsSucceedOrAreReplaced) {
  const std::string session = demo_session();
  std::atomic<int> sessions{0}, made{0}, replaced{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < 20; ++i)
    threads.emplace_back([&, i] {
      auto c = client();
      // A mix: new sessions, makes on one shared session with different seeds.
      httplib::Result res = i % 3 == 0 ? c.Post("/api/demo", "", "application/json")
                            : i % 3 == 1
                                ? c.Post("/api/make", json{{"session", session}, {"seed", i}, {"mode", "constant-ribbon"}}.dump(),
                                         "application/json")
                                : c.Post("/api/make", json{{"session", session}, {"seed", i}}.dump(), "application/json");
      if (!res) return;
      if (i % 3 == 0) sessions += res->status == 200;
      else if (res->status == 200) ++made;
      else if (res->status == 409 && json::parse(res->body).value("cancelled", false)) ++replaced;
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(sessions.load(), 7);
  EXPECT_GE(made.load(), 1);
  EXPECT_EQ(made.load() + replaced.load(), 13);
  const auto view = client().Get("/api/result/" + session + "/view.bin");
  ASSERT_TRUE(view);
  EXPECT_EQ(view->status, 200);
  EXPECT_EQ(view->body.substr(0, 4), "MND3");
}

TEST(StudioRequestRefusal, HostMustNameThisServer) {
  const std::string origin = "http://127.0.0.1:8080";
  for (const char* host : {"127.0.0.1", "127.0.0.1:8080", "localhost:8080", "localhost", "[::1]:8080"})
    EXPECT_EQ(studio_request_refusal("127.0.0.1", 8080, "POST", host, &origin), "") << host;
  for (const char* host : {"evil.example", "evil.example:8080", "127.0.0.1:9090", "127.0.0.1.evil.example:8080", "",
                           "192.168.1.5:8080", "localhost:8080:8080"})
    EXPECT_NE(studio_request_refusal("127.0.0.1", 8080, "GET", host, nullptr).find("is not this server"), std::string::npos)
        << host;
  // --host 192.168.1.5: that address too, and an IPv6 one in brackets.
  EXPECT_EQ(studio_request_refusal("192.168.1.5", 8080, "GET", "192.168.1.5:8080", nullptr), "");
  EXPECT_EQ(studio_request_refusal("fd00::5", 8080, "GET", "[fd00::5]:8080", nullptr), "");
  EXPECT_NE(studio_request_refusal("192.168.1.5", 8080, "GET", "evil.example:8080", nullptr), "");
}

TEST(StudioRequestRefusal, StateChangesNeedOurOwnOrigin) {
  for (const char* origin : {"http://127.0.0.1:8080", "http://localhost:8080"}) {
    const std::string o = origin;
    EXPECT_EQ(studio_request_refusal("127.0.0.1", 8080, "POST", "127.0.0.1:8080", &o), "") << origin;
  }
  for (const char* origin : {"http://evil.example", "null", "https://127.0.0.1:8080", "http://127.0.0.1:9090",
                             "http://evil.example:8080", ""}) {
    const std::string o = origin;
    EXPECT_NE(studio_request_refusal("127.0.0.1", 8080, "POST", "127.0.0.1:8080", &o).find("cross-site requests are refused"),
              std::string::npos)
        << origin;
    EXPECT_EQ(studio_request_refusal("127.0.0.1", 8080, "GET", "127.0.0.1:8080", &o), "") << origin;
  }
  // Scripts (curl, Python) send no Origin.
  EXPECT_EQ(studio_request_refusal("127.0.0.1", 8080, "POST", "127.0.0.1:8080", nullptr), "");
}

TEST_F(StudioServerTest, ForeignHostOrOriginGets403OverHttp) {
  auto c = client();
  const std::string port = std::to_string(port_);
  // DNS rebinding: the browser sends the attacker's name as Host.
  const auto rebound = c.Get("/api/info", {{"Host", "evil.example:" + port}});
  ASSERT_TRUE(rebound);
  EXPECT_EQ(rebound->status, 403);
  EXPECT_NE(error_of(rebound).find("Host 'evil.example:" + port + "' is not this server"), std::string::npos) << rebound->body;
  const auto page = c.Get("/", {{"Host", "evil.example:" + port}});
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 403);
  // A cross-site POST from a page the user visits.
  const auto forged = c.Post("/api/demo", {{"Origin", "http://evil.example"}}, "", "application/json");
  ASSERT_TRUE(forged);
  EXPECT_EQ(forged->status, 403);
  EXPECT_EQ(error_of(forged), "Origin 'http://evil.example' is not this server's own page: cross-site requests are refused");
  // The page itself, by either name.
  for (const std::string& origin : {"http://127.0.0.1:" + port, "http://localhost:" + port}) {
    const auto own = c.Post("/api/demo", {{"Origin", origin}}, "", "application/json");
    ASSERT_TRUE(own);
    EXPECT_EQ(own->status, 200) << origin << ": " << own->body;
  }
  const auto by_name = c.Get("/api/info", {{"Host", "localhost:" + port}});
  ASSERT_TRUE(by_name);
  EXPECT_EQ(by_name->status, 200);
}

// Cancel and replace (docs/studio.md, "Cancel"): a job held in flight by the test hook
// (never a slow job: no test waits on a time) is cancelled by a newer request, by
// /api/cancel, or by its client going away, and answered 409 {"cancelled": true}.
class StudioCancelTest : public StudioServerTest {
protected:
  void SetUp() override {
    running_ = std::make_unique<RunningServer>(StudioServerOptions{.port = 0, .max_upload = 1 << 20, .test_hooks = true});
    port_ = running_->port;
  }
  std::string held_request(const std::string& session) const {
    return json{{"session", session}, {"mode", "constant-wire"}, {"hold", true}}.dump();
  }
  // Until the session has a job in flight, which has begun a stage.
  json wait_until_busy(const std::string& session) const {
    for (auto c = client();;) {
      const auto res = c.Get("/api/progress/" + session);
      if (!res || res->status != 200) return json();
      const json progress = json::parse(res->body);
      if (progress["busy"] == true && !progress["stage"].get<std::string>().empty()) return progress;
      std::this_thread::sleep_for(std::chrono::milliseconds(10)); // a lighter poll, not a deadline
    }
  }
  void wait_until_idle(const std::string& session) const {
    for (auto c = client();;) {
      const auto res = c.Get("/api/progress/" + session);
      if (!res || res->status != 200 || json::parse(res->body)["busy"] == false) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(10)); // a lighter poll, not a deadline
    }
  }
};

TEST_F(StudioCancelTest, ANewerRequestCancelsTheJobInFlight) {
  const std::string session = demo_session();
  std::optional<httplib::Result> held;
  std::thread first([&] { held.emplace(client().Post("/api/make", held_request(session), "application/json")); });
  const json progress = wait_until_busy(session);
  EXPECT_EQ(progress["stage"], "quadrangulate");
  EXPECT_EQ(progress["fraction"], -1.0);
  const auto newer = client().Post("/api/make", json{{"session", session}, {"mode", "curve"}, {"seed", 3}}.dump(), "application/json");
  first.join();
  ASSERT_TRUE(held && *held);
  EXPECT_EQ((*held)->status, 409) << (*held)->body;
  EXPECT_EQ(json::parse((*held)->body)["cancelled"], true);
  ASSERT_TRUE(newer);
  ASSERT_EQ(newer->status, 200) << newer->body;
  EXPECT_EQ(json::parse(newer->body)["mode"], "curve");
  // The session holds the newer result, and nothing is in flight.
  EXPECT_EQ(json::parse(client().Get("/api/progress/" + session)->body)["busy"], false);
  const auto view = client().Get("/api/result/" + session + "/view.bin");
  ASSERT_TRUE(view);
  const test::DecodedView drawn = test::decode_view(view->body);
  EXPECT_EQ(drawn.triangles, 0u) << "the view is the curve's, not the held wire's";
  EXPECT_GT(drawn.segments, 0u);
}

TEST_F(StudioCancelTest, CancelStopsTheJobInFlight) {
  const std::string session = demo_session();
  const auto none = client().Post("/api/cancel/" + session, "", "application/json");
  ASSERT_TRUE(none);
  EXPECT_EQ(json::parse(none->body)["cancelled"], false);
  std::optional<httplib::Result> held;
  std::thread first([&] { held.emplace(client().Post("/api/make", held_request(session), "application/json")); });
  wait_until_busy(session);
  const auto cancelled = client().Post("/api/cancel/" + session, "", "application/json");
  first.join();
  ASSERT_TRUE(cancelled);
  EXPECT_EQ(json::parse(cancelled->body)["cancelled"], true);
  ASSERT_TRUE(held && *held);
  EXPECT_EQ((*held)->status, 409) << (*held)->body;
  EXPECT_EQ(client().Get("/api/result/" + session + "/view.bin")->status, 409) << "nothing made in the session";
  EXPECT_EQ(client().Post("/api/cancel/nosuchsession", "", "application/json")->status, 404);
  EXPECT_EQ(client().Get("/api/progress/nosuchsession")->status, 404);
}

TEST_F(StudioCancelTest, AClientThatGoesAwayTakesItsJobWithIt) {
  const std::string session = demo_session();
  const std::string body = held_request(session);
  {
    test::RawConnection connection(port_);
    connection.send("POST /api/make HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: " +
                    std::to_string(body.size()) + "\r\n\r\n" + body);
    wait_until_busy(session);
  } // closed
  wait_until_idle(session); // ctest's timeout ends the test if the job never stops
  EXPECT_EQ(client().Get("/api/result/" + session + "/view.bin")->status, 409) << "nothing made in the session";
}

TEST_F(StudioServerTest, HoldIsOnlyForTests) {
  const std::string session = demo_session();
  const auto res = client().Post("/api/make", json{{"session", session}, {"hold", true}}.dump(), "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_EQ(error_of(res), "hold: only for tests of clients (a server started with --test-hooks)");
}

TEST(StudioServerLimits, LargeUploadsAndResultsAreRefusedWithAMessage) {
  RunningServer running({.port = 0, .max_faces = 2, .max_pixels = 1000, .max_result = 200'000});
  httplib::Client c = test::client_of(running.port);
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  const auto two = c.Post("/api/mesh", httplib::MultipartFormDataItems{{"mesh", square, "square.obj", ""}});
  ASSERT_TRUE(two);
  EXPECT_EQ(two->status, 200) << two->body;
  const auto three = c.Post("/api/mesh", httplib::MultipartFormDataItems{{"mesh", square + "f 2 3 4\n", "three.obj", ""}});
  ASSERT_TRUE(three);
  EXPECT_EQ(three->status, 422);
  EXPECT_EQ(json::parse(three->body)["error"], "three.obj: 3 faces, more than the limit of 2");
  Image wide{.width = 2000, .height = 1, .rgba = std::vector<uint8_t>(2000 * 4, 128)};
  const auto picture = c.Post("/api/mesh", httplib::MultipartFormDataItems{{"mesh", png_file_bytes(wide), "wide.png", ""}});
  ASSERT_TRUE(picture);
  EXPECT_EQ(picture->status, 422);
  EXPECT_NE(json::parse(picture->body)["error"].get<std::string>().find("wide.png: "), std::string::npos) << picture->body;
  // The demo (1,600 faces) is the server's own; what a request asks of it is bounded.
  const auto demo = c.Post("/api/demo", "", "application/json");
  ASSERT_TRUE(demo);
  const std::string session = json::parse(demo->body)["session"];
  const auto fine = c.Post("/api/make", json{{"session", session}, {"mode", "variable-ribbon"}, {"levels", 0}}.dump(), "application/json");
  ASSERT_TRUE(fine);
  EXPECT_EQ(fine->status, 200) << fine->body;
  for (const json& greedy : {json{{"mode", "variable-wire"}, {"levels", 6}}, json{{"mode", "curve"}, {"samples", 1000}},
                             json{{"mode", "constant-wire"}, {"sides", 64}, {"samples", 16}},
                             json{{"mode", "duotone"}, {"texture_size", 8192}}}) {
    json request = greedy;
    request["session"] = session;
    const auto res = c.Post("/api/make", request.dump(), "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 413) << greedy.dump();
    EXPECT_NE(json::parse(res->body)["error"].get<std::string>().find("more than this server's --max-result of 200000"),
              std::string::npos)
        << res->body;
  }
  // A preview of the same asks for little: levels 0.
  const auto preview = c.Post("/api/make", json{{"session", session}, {"mode", "variable-wire"}, {"levels", 6}, {"preview", true}}.dump(),
                              "application/json");
  ASSERT_TRUE(preview);
  EXPECT_EQ(preview->status, 200) << preview->body;
  EXPECT_EQ(json::parse(preview->body)["preview"], true);
}

} // namespace
} // namespace meander
