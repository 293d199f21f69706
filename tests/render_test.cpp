// The renderer: deterministic bytes, a fitted camera (a sphere's mask is a centred disc
// of the expected size), occluders that hide without being drawn, precise refusals,
// and `meander render` / `meander curve --png` from the command line.
#include "meander/error.h"
#include "meander/io.h"
#include "meander/render.h"
#include "meander/shapes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <array>
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
  behind.meshes.push_back({.mesh = sphere(4000), .style = MeshStyle::hidden});
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
  } catch (const NoPolylinesError& e) { // what `meander render` then reads as a mesh
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

// The bounding box of the pixels that are not background.
struct Extent {
  int lo_x = 1 << 30, hi_x = -1, lo_y = 1 << 30, hi_y = -1;
  double centre_x() const { return (lo_x + hi_x) / 2.0; }
  double centre_y() const { return (lo_y + hi_y) / 2.0; }
};
Extent object_extent(const Image& image) {
  Extent e;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!is_background(image, x, y))
        e.lo_x = std::min(e.lo_x, x), e.hi_x = std::max(e.hi_x, x), e.lo_y = std::min(e.lo_y, y), e.hi_y = std::max(e.hi_y, y);
  return e;
}

TEST(RenderFraming, FitFillsThePictureWithTheSilhouetteCentred) {
  // Tricky: a torus seen from above at an angle is wider than tall and its near side
  // projects larger than its far side, so centring its bounds does not centre its picture.
  Scene scene;
  scene.meshes.push_back({.mesh = torus(3000)});
  RenderOptions options{.width = 200, .height = 200, .view = parse_view("20,50"), .samples = 1};
  const Extent bounds = object_extent(render(scene, options));
  options.framing = Framing::silhouette;
  const Extent fit = object_extent(render(scene, options));
  // The wider side touches the 3% margins; the other side is centred.
  EXPECT_NEAR(fit.hi_x - fit.lo_x + 1, 0.94 * 200, 2.5);
  EXPECT_NEAR(fit.centre_x(), 99.5, 1.5);
  EXPECT_NEAR(fit.centre_y(), 99.5, 1.5);
  EXPECT_GT(fit.hi_x - fit.lo_x, bounds.hi_x - bounds.lo_x + 6);
}

TEST(RenderFraming, SphereFramingKeepsTheDistanceWhateverTheView) {
  // A long box: its outline changes a lot as it turns, the camera's distance must not,
  // and no view may cut it.
  PolygonMesh box;
  for (int i = 0; i < 8; ++i) box.positions.push_back({i & 1 ? 2.f : -2.f, i & 2 ? 0.3f : -0.3f, i & 4 ? 0.3f : -0.3f});
  for (auto f : {std::array{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}})
    box.add_face(f);
  Scene scene;
  scene.meshes.push_back({.mesh = box});
  RenderOptions options{.width = 160, .height = 120, .samples = 1, .framing = Framing::sphere};
  for (int azimuth = 0; azimuth < 360; azimuth += 30) {
    options.view = {double(azimuth), 20};
    const Extent e = object_extent(render(scene, options));
    EXPECT_GE(std::min({e.lo_x, e.lo_y, 159 - e.hi_x, 119 - e.hi_y}), 6) << azimuth;
  }
  // From the front, the bounding sphere (radius sqrt(4.18)) fills 88% of the height at
  // distance d; the box's front face, 4 units long at depth d - 0.3, takes its share.
  options.view = parse_view("front");
  const Extent front = object_extent(render(scene, options));
  const double tan_half = std::tan(12.5 * std::numbers::pi / 180);
  const double d = std::sqrt(4.18) / std::sin(std::atan(0.88 * tan_half));
  EXPECT_NEAR(front.hi_x - front.lo_x + 1, 4 / (d - 0.3) / (2 * tan_half) * 120, 2);
  EXPECT_NEAR(front.centre_x(), 79.5, 1);
}

TEST(RenderTurntable, FramesAreNumberedDeterministicAndStartAtTheStill) {
  EXPECT_EQ(turntable_frame_path("out/spin.png", 7, 36), fs::path("out/spin_007.png"));
  EXPECT_EQ(turntable_frame_path("spin.png", 999, 1000), fs::path("spin_999.png"));
  EXPECT_EQ(turntable_frame_path("spin.png", 7, 1001), fs::path("spin_0007.png"));

  Scene scene;
  scene.meshes.push_back({.mesh = torus(800)});
  scene.curves.push_back({.curves = circle_on_sphere(0.2)});
  const RenderOptions options{.width = 64, .height = 48, .view = parse_view("30,20"), .samples = 2};
  const auto dir = output_dir();
  const auto frames = write_turntable(scene, options, 4, dir / "t.png");
  ASSERT_EQ(frames.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(fs::exists(dir / ("t_00" + std::to_string(k) + ".png")));
  const std::string first = test::read_file(frames[0]), second = test::read_file(frames[1]);
  write_turntable(scene, options, 4, dir / "again.png");
  EXPECT_EQ(test::read_file(dir / "again_000.png"), first);
  EXPECT_EQ(test::read_file(dir / "again_001.png"), second);
  EXPECT_NE(first, second);
  RenderOptions still = options;
  still.framing = Framing::sphere;
  write_png(render(scene, still), dir / "still.png");
  EXPECT_EQ(test::read_file(dir / "still.png"), first);

  EXPECT_THROW(write_turntable(scene, options, 0, dir / "none.png"), UsageError);
  EXPECT_THROW(write_turntable(scene, options, 2, dir / "none.jpg"), UsageError);
  EXPECT_FALSE(fs::exists(dir / "none_000.png"));
  EXPECT_FALSE(fs::exists(dir / "none_000.jpg"));
}

// Runs of object pixels down column x: their lengths, top to bottom.
std::vector<int> vertical_runs(const Image& image, int x) {
  std::vector<int> runs;
  bool inside = false;
  for (int y = 0; y < image.height; ++y) {
    // At least half covered: the run's length is then the curve's width, not its blur.
    const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
    const bool object = p[1] < 190;
    if (object && !inside) runs.push_back(0);
    if (object) ++runs.back();
    inside = object;
  }
  return runs;
}

TEST(RenderCurveStyle, RibbonsKeepTheirPixelWidthAtAnyDepthTubesDoNot) {
  // Two straight open segments across the view, one three times as far as the other.
  Scene scene;
  Polylines lines;
  lines.points = {{-1, 0.6f, 2}, {1, 0.6f, 2}, {-3, -1.2f, -4}, {3, -1.2f, -4}};
  lines.start = {0, 2, 4};
  lines.open = {1, 1};
  scene.curves.push_back({.curves = lines});
  RenderOptions options{.width = 160, .height = 160, .view = parse_view("front"), .samples = 16, .curve_width = 6};
  options.curve_style = CurveStyle::ribbon;
  const std::vector<int> ribbon = vertical_runs(render(scene, options), 80);
  ASSERT_EQ(ribbon.size(), 2u);
  EXPECT_NEAR(ribbon[0], 6, 1);
  EXPECT_NEAR(ribbon[1], 6, 1);
  options.curve_style = CurveStyle::tube;
  const std::vector<int> tube = vertical_runs(render(scene, options), 80);
  ASSERT_EQ(tube.size(), 2u);
  EXPECT_GT(tube[0], tube[1] + 2); // the near tube is thicker
}

TEST(RenderOccluder, FaintShowsTheSurfaceInLightGreyAndStillHidesTheCurveBehind) {
  const RenderOptions options{.width = 160, .height = 120, .view = parse_view("front"), .curve_width = 4};
  auto red_pixels = [](const Image& image) {
    int64_t count = 0;
    for (size_t i = 0; i < image.rgba.size(); i += 4) count += image.rgba[i] > image.rgba[i + 1] + 40;
    return count;
  };
  for (const CurveStyle style : {CurveStyle::tube, CurveStyle::ribbon}) {
    Scene scene;
    scene.meshes.push_back({.mesh = sphere(4000), .style = MeshStyle::faint});
    scene.curves.push_back({.curves = circle_on_sphere(-0.6)});
    RenderOptions o = options;
    o.curve_style = style;
    const Image faint = render(scene, o);
    EXPECT_EQ(red_pixels(faint), 0);
    int64_t light_grey = 0;
    for (size_t i = 0; i < faint.rgba.size(); i += 4) {
      const uint8_t r = faint.rgba[i], g = faint.rgba[i + 1], b = faint.rgba[i + 2];
      light_grey += r == g && g == b && r >= 200 && r < 250;
    }
    // The sphere's disc (about 0.88 * 120 pixels across) is light grey.
    EXPECT_GT(light_grey, 0.8 * 3.14159 / 4 * (0.88 * 120) * (0.88 * 120));
    scene.meshes[0].style = MeshStyle::hidden;
    EXPECT_EQ(object_pixels(render(scene, o)), 0);
    // In front of the surface, the curve shows over the faint grey.
    scene.meshes[0].style = MeshStyle::faint;
    scene.curves[0].curves = circle_on_sphere(0.6);
    EXPECT_GT(red_pixels(render(scene, o)), 200);
  }
}

TEST(RenderCli, PlyCurvesTurntablesAndStyles) {
  const auto dir = output_dir();
  const auto mesh = dir / "sphere.obj", curve = dir / "curve.ply", png = dir / "out.png";
  ASSERT_EQ(run_cli({"generate", "sphere", "--faces", "400", "-o", mesh.string()}).exit_code, 0);
  ASSERT_EQ(run_cli({"curve", mesh.string(), "-o", curve.string()}).exit_code, 0);
  const auto styled = run_cli({"render", curve.string(), "--occluder", mesh.string(), "--occluder-style", "faint",
                               "--curve-style", "ribbon", "--fit", "-o", png.string(), "--size", "80x60"});
  ASSERT_EQ(styled.exit_code, 0) << styled.err;
  EXPECT_EQ(png_size(test::read_file(png)), std::make_pair(80u, 60u));

  const auto spin = run_cli({"render", curve.string(), "--occluder", mesh.string(), "-o", (dir / "spin.png").string(),
                             "--size", "48x36", "--turntable", "3", "--view", "front", "--samples", "1"});
  ASSERT_EQ(spin.exit_code, 0) << spin.err;
  for (const char* frame : {"spin_000.png", "spin_001.png", "spin_002.png"}) EXPECT_TRUE(fs::exists(dir / frame));
  EXPECT_FALSE(fs::exists(dir / "spin.png"));
  // The first frame is the still picture from that view, framed on the bounding sphere.
  Scene scene;
  scene.meshes.push_back({.mesh = read_mesh(mesh), .style = MeshStyle::hidden});
  scene.curves.push_back({.curves = read_polylines(curve)});
  write_png(render(scene, {.width = 48, .height = 36, .view = parse_view("front"), .samples = 1, .framing = Framing::sphere}),
            dir / "still.png");
  EXPECT_EQ(test::read_file(dir / "spin_000.png"), test::read_file(dir / "still.png"));

  const auto frames = run_cli({"curve", mesh.string(), "-o", (dir / "c.obj").string(), "--png", (dir / "f.png").string(),
                               "--turntable", "2", "--size", "40x30", "--occluder-style", "faint"});
  ASSERT_EQ(frames.exit_code, 0) << frames.err;
  EXPECT_TRUE(fs::exists(dir / "f_000.png"));
  EXPECT_TRUE(fs::exists(dir / "f_001.png"));

  // Usage errors: a tight fit cannot keep a turntable's distance, styles are checked,
  // picture options need --png.
  EXPECT_EQ(run_cli({"render", mesh.string(), "-o", png.string(), "--fit", "--turntable", "2"}).exit_code, 2);
  EXPECT_EQ(run_cli({"render", mesh.string(), "-o", png.string(), "--curve-style", "wire"}).exit_code, 2);
  EXPECT_EQ(run_cli({"render", mesh.string(), "-o", png.string(), "--occluder-style", "ghost"}).exit_code, 2);
  EXPECT_EQ(run_cli({"curve", mesh.string(), "-o", (dir / "d.obj").string(), "--turntable", "2"}).exit_code, 2);

  // A malformed PLY curve is refused by the curve reader, naming the edge; no picture.
  const auto branch = test::write_file("branch.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                                                     "property float y\nproperty float z\nelement edge 3\n"
                                                     "property int vertex1\nproperty int vertex2\nend_header\n"
                                                     "0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 1\n0 2\n0 3\n");
  const auto refused = run_cli({"render", branch.string(), "-o", (dir / "branch.png").string()});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find(branch.string() + ": edge 2: vertex 0 already joins edges 0 and 1"), std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir / "branch.png"));
}

} // namespace
} // namespace meander
