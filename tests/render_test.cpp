// The renderer: deterministic bytes, a fitted camera (a sphere's mask is a centred disc
// of the expected size), occluders that hide without being drawn, precise refusals,
// and `meander render` / `meander curve --png` from the command line.
#include "meander/error.h"
#include "meander/io.h"
#include "meander/render.h"
#include "meander/shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace meander {
namespace {

namespace fs = std::filesystem;
using test::output_dir;
using test::run_cli;

bool is_background(const Image& image, int x, int y) {
  const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
  return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

int64_t object_pixels(const Image& image) {
  int64_t count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) count += !is_background(image, x, y);
  return count;
}

// A circle of radius r on the unit sphere at height z (|z| = sqrt(1 - r^2)).
Polylines circle_on_sphere(double z) {
  Polylines c;
  const double r = std::sqrt(1 - z * z);
  for (int i = 0; i < 200; ++i) {
    const double t = 2 * std::numbers::pi * i / 200;
    c.points.push_back({float(r * std::cos(t)), float(r * std::sin(t)), float(z)});
  }
  c.start.push_back(int32_t(c.points.size()));
  return c;
}

TEST(Render, SameInputGivesSameBytes) {
  Scene scene;
  scene.meshes.push_back({.mesh = sphere(2000)});
  scene.curves.push_back({.curves = circle_on_sphere(0.5)});
  const RenderOptions options{.width = 120, .height = 90, .samples = 3};
  const Image a = render(scene, options), b = render(scene, options);
  EXPECT_EQ(a.rgba, b.rgba);
  const auto dir = output_dir();
  write_png(a, dir / "a.png");
  write_png(b, dir / "b.png");
  EXPECT_EQ(test::read_file(dir / "a.png"), test::read_file(dir / "b.png"));
}

TEST(Render, SphereMaskIsACentredDiscFittedToThePicture) {
  Scene scene;
  scene.meshes.push_back({.mesh = sphere(20000)});
  const Image image = render(scene, {.width = 240, .height = 180, .view = parse_view("front"), .samples = 1});
  int lo_x = image.width, hi_x = -1, lo_y = image.height, hi_y = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!is_background(image, x, y)) lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x), lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
  const double width = hi_x - lo_x + 1, height = hi_y - lo_y + 1;
  // The camera leaves a 6% margin on each side of the limiting (vertical) extent.
  EXPECT_NEAR(height, 0.88 * image.height, 3);
  EXPECT_NEAR(width, height, 2);
  EXPECT_NEAR((lo_x + hi_x) / 2.0, (image.width - 1) / 2.0, 1.5);
  EXPECT_NEAR((lo_y + hi_y) / 2.0, (image.height - 1) / 2.0, 1.5);
  const double disc = std::numbers::pi * width * height / 4;
  EXPECT_NEAR(double(object_pixels(image)), disc, 0.03 * disc);
}

TEST(Render, OccluderHidesTheCurveBehindItAndIsNotDrawn) {
  // Tricky: the occluder is hit first by every ray that would reach the back circle,
  // and it must not show itself either, so the whole picture stays background.
  const RenderOptions options{.width = 160, .height = 120, .view = parse_view("front"), .curve_width = 4};
  Scene behind;
  behind.meshes.push_back({.mesh = sphere(4000), .occluder_only = true});
  behind.curves.push_back({.curves = circle_on_sphere(-0.6)});
  EXPECT_EQ(object_pixels(render(behind, options)), 0);

  Scene in_front = behind;
  in_front.curves[0].curves = circle_on_sphere(0.6);
  EXPECT_GT(object_pixels(render(in_front, options)), 200);

  Scene unoccluded = behind;
  unoccluded.meshes.clear();
  EXPECT_GT(object_pixels(render(unoccluded, options)), 200);
}

TEST(Render, TransparentBackgroundHasCoverageAlpha) {
  Scene scene;
  scene.meshes.push_back({.mesh = sphere(2000)});
  const Image image = render(scene, {.width = 64, .height = 48, .background = parse_background("transparent")});
  EXPECT_TRUE(image.has_alpha);
  EXPECT_EQ(image.rgba[3], 0);                                    // a corner
  EXPECT_EQ(image.rgba[(size_t(24) * 64 + 32) * 4 + 3], 255);     // the centre
}

TEST(Render, BadOptionsGivePreciseErrors) {
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no UsageError");
  };
  int32_t w = 0, h = 0;
  EXPECT_EQ(message([&] { parse_size("0x0", w, h); }), "size '0x0': expected WIDTHxHEIGHT, each 1..16384 pixels");
  EXPECT_EQ(message([&] { parse_size("800x", w, h); }), "size '800x': expected WIDTHxHEIGHT, each 1..16384 pixels");
  EXPECT_EQ(message([] { parse_view("sideways"); }),
            "view 'sideways': expected front, back, left, right, top, iso or AZ,EL in degrees (elevation -90..90)");
  EXPECT_EQ(message([] { parse_view("10,95"); }),
            "view '10,95': expected front, back, left, right, top, iso or AZ,EL in degrees (elevation -90..90)");
  EXPECT_EQ(message([] { parse_background("#12345"); }), "background '#12345': expected white, transparent or #rrggbb");
  EXPECT_EQ(message([] { parse_background("#12345g"); }), "background '#12345g': expected white, transparent or #rrggbb");
  EXPECT_EQ(message([] { render(Scene{}, {.width = 0, .height = 0}); }),
            "image size 0x0: width and height must be 1..16384 pixels");
  const auto dir = output_dir();
  EXPECT_EQ(message([&] { write_png(Image{.width = 1, .height = 1, .rgba = {0, 0, 0, 255}}, dir / "x.jpg"); }),
            (dir / "x.jpg").string() + ": unknown image format '.jpg' (expected .png)");
  EXPECT_FALSE(fs::exists(dir / "x.jpg"));

  EXPECT_EQ(parse_view("30,-20").azimuth, 30);
  EXPECT_EQ(parse_view("30,-20").elevation, -20);
  EXPECT_FLOAT_EQ(parse_background("#ff8000").color.g, 128.0f / 255);
}

TEST(ReadPolylines, RoundTripsWhatWritePolylinesWrites) {
  Polylines curves = circle_on_sphere(0.3);
  curves.points.push_back({1, 2, 3});
  curves.points.push_back({4, 5, 6});
  curves.start.push_back(int32_t(curves.points.size()));
  const auto path = output_dir() / "curves.obj";
  write_polylines(curves, path);
  const Polylines back = read_polylines(path);
  EXPECT_EQ(back.start, curves.start);
  EXPECT_EQ(back.points, curves.points);
}

TEST(ReadPolylines, RefusesAFileWithoutLines) {
  const auto path = test::write_file("faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  try {
    read_polylines(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ": no polylines (l elements)");
  }
  const auto short_line = test::write_file("short.obj", "v 0 0 0\nl 1\n");
  try {
    read_polylines(short_line);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), short_line.string() + ":2: line with 1 vertices (at least 2 needed)");
  }
}

// The PNG's width and height from its IHDR chunk.
std::pair<uint32_t, uint32_t> png_size(const std::string& bytes) {
  auto be32 = [&](size_t at) {
    return uint32_t(uint8_t(bytes[at])) << 24 | uint32_t(uint8_t(bytes[at + 1])) << 16 |
           uint32_t(uint8_t(bytes[at + 2])) << 8 | uint32_t(uint8_t(bytes[at + 3]));
  };
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return {0, 0};
  return {be32(16), be32(20)};
}

TEST(RenderCli, RendersAMeshWithItsCurveAndTheCurveCommandRendersToo) {
  const auto dir = output_dir();
  const auto mesh = dir / "pretzel.obj", curve = dir / "curve.obj", png = dir / "curve.png", both = dir / "both.png";
  ASSERT_EQ(run_cli({"generate", "pretzel", "--faces", "1600", "-o", mesh.string()}).exit_code, 0);
  const auto made = run_cli({"curve", mesh.string(), "-o", curve.string(), "--png", png.string()});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  EXPECT_EQ(png_size(test::read_file(png)), std::make_pair(1600u, 1200u));
  const auto small = dir / "small.png";
  const auto sized = run_cli({"curve", mesh.string(), "-o", curve.string(), "--png", small.string(), "--size", "320x200", "--view", "top"});
  ASSERT_EQ(sized.exit_code, 0) << sized.err;
  EXPECT_EQ(png_size(test::read_file(small)), std::make_pair(320u, 200u));
  // A bad picture option is refused before any work: no curve, no picture.
  const auto refused = dir / "refused.obj";
  EXPECT_EQ(run_cli({"curve", mesh.string(), "-o", refused.string(), "--png", (dir / "r.png").string(), "--view", "sideways"}).exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(refused));
  EXPECT_FALSE(std::filesystem::exists(dir / "r.png"));

  const auto r = run_cli({"render", curve.string(), "--occluder", mesh.string(), "-o", both.string(), "--size",
                          "200x100", "--view", "top", "--background", "#202020", "--samples", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(png_size(test::read_file(both)), std::make_pair(200u, 100u));
}

TEST(RenderCli, BadOptionsAreUsageErrorsAndLeaveNoPicture) {
  const auto dir = output_dir();
  const auto mesh = dir / "sphere.obj", png = dir / "out.png";
  ASSERT_EQ(run_cli({"generate", "sphere", "--faces", "200", "-o", mesh.string()}).exit_code, 0);
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--size", "0x0"}, "size '0x0'"},
      {{"--view", "sideways"}, "view 'sideways'"},
      {{"--background", "#12345"}, "background '#12345'"},
  };
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"render", mesh.string(), "-o", png.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << message;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(png)) << message;
  }
  const auto wrong = run_cli({"render", mesh.string(), "-o", (dir / "out.jpg").string()});
  EXPECT_EQ(wrong.exit_code, 2);
  const auto no_file = run_cli({"render", (dir / "missing.obj").string(), "-o", png.string()});
  EXPECT_EQ(no_file.exit_code, 1);
  EXPECT_FALSE(fs::exists(png));
}

} // namespace
} // namespace meander
