// Plotter drawings (drawing.h, `meander draw`): hidden parts removed, the sheet's
// layout, and the SVG read back by a parser of the test's own.
#include "test_support.h"

#include "meander/drawing.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/pipeline.h"
#include "meander/shapes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace meander {
namespace {

using test::output_dir;
using test::read_file;
using test::read_svg_paths;
using test::run_cli;
using test::SvgPath;

// n points of a circle of radius r round the axis `axis` (0 x, 1 y, 2 z) at height h.
Polylines circle(int axis, double r, double h, int n = 360) {
  Polylines c;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n, a = r * std::cos(t), b = r * std::sin(t);
    const std::array<double, 3> p = axis == 2 ? std::array{a, b, h} : axis == 1 ? std::array{a, h, b} : std::array{h, a, b};
    c.points.push_back({float(p[0]), float(p[1]), float(p[2])});
  }
  c.start.push_back(n);
  return c;
}

DrawingOptions front() { return {.view = {.azimuth = 0, .elevation = 0}}; }

TEST(Drawing, ACircleOnTheFarSideOfASphereIsHiddenAndOneOnTheNearSideDrawnWhole) {
  const PolygonMesh sphere = meander::sphere(8000);
  // Seen from +z: circles of the unit sphere at z = 0.6 (near) and -0.6 (far).
  const Drawing near = draw_curves(circle(2, 0.8, 0.6), sphere, front());
  ASSERT_EQ(near.size(), 1);
  EXPECT_TRUE(near.closed[0]);
  const Drawing far = draw_curves(circle(2, 0.8, -0.6), sphere, front());
  EXPECT_EQ(far.size(), 0);
  EXPECT_EQ(far.drawn_length, 0);
}

TEST(Drawing, NothingBehindATorusFrontTubeIsDrawn) {
  const PolygonMesh torus = meander::torus(8000); // round the z axis, tube radius 0.35
  // Seen edge-on from +x, the far half of the ring lies behind the near tube: of the
  // outer equator (radius 1.35), the arc where x < 0 is hidden, the one where x > 0 drawn.
  const DrawingOptions side{.view = {.azimuth = 90, .elevation = 0}};
  Polylines back, front_half;
  for (int i = 0; i <= 100; ++i) {
    const double t = std::numbers::pi * (0.2 + 0.6 * i / 100); // 36 to 144 degrees from +y
    back.points.push_back({float(-1.35 * std::sin(t)), float(1.35 * std::cos(t)), 0});
    front_half.points.push_back({float(1.35 * std::sin(t)), float(1.35 * std::cos(t)), 0});
  }
  back.start.push_back(101), back.open = {1};
  front_half.start.push_back(101), front_half.open = {1};
  EXPECT_EQ(draw_curves(back, torus, side).size(), 0);
  const Drawing drawn = draw_curves(front_half, torus, side);
  ASSERT_EQ(drawn.size(), 1);
  EXPECT_FALSE(drawn.closed[0]);
}

// The length drawn of a sphere's curve (seen from the front) at a number of samples per segment.
double drawn_length(int samples) {
  CurveJob job;
  job.curve.samples = samples;
  const CurveResult result = make_curve(meander::sphere(3000), job);
  return draw_curves(result.curves, cycle_triangles(result.quads, result.cycle), front()).drawn_length;
}

TEST(Drawing, SamplingTheCurveAtHalfOrTwiceTheStepChangesTheDrawnLengthByUnderOnePercent) {
  const double at_default = drawn_length(4);
  EXPECT_NEAR(drawn_length(2), at_default, 0.01 * at_default);
  EXPECT_NEAR(drawn_length(8), at_default, 0.01 * at_default);
}

TEST(Drawing, APaperNoLargerThanItsMarginsOrABadPenIsRefused) {
  const Polylines c = circle(2, 1, 0);
  DrawingOptions options = front();
  options.paper = {.width = 20, .height = 300, .margin = 10};
  EXPECT_THROW(draw_curves(c, {}, options), UsageError);
  options.paper = {};
  options.pen = 0;
  EXPECT_THROW(draw_curves(c, {}, options), UsageError);
  EXPECT_THROW(parse_paper("B7"), UsageError);
  EXPECT_THROW(parse_paper("300x"), UsageError);
  const Paper letter = parse_paper("Letter", true);
  EXPECT_DOUBLE_EQ(letter.width, 279.4);
  EXPECT_DOUBLE_EQ(letter.height, 215.9);
  EXPECT_DOUBLE_EQ(parse_paper("300x200mm").width, 200); // portrait unless landscape
}

// The paths of an SVG as the test reads them: each <path d="M x y L x y ... [Z]"> inside
// a layer <g inkscape:groupmode="layer">.
TEST(CliDraw, APlotterDrawingOfAMeshFitsItsSheetOneLayerPerComponent) {
  const auto dir = output_dir();
  const std::string mesh = (dir / "two.obj").string(), svg = (dir / "two.svg").string(), png = (dir / "two.png").string();
  write_mesh(test::side_by_side(meander::sphere(800), meander::torus(800), {3, 0, 0}), mesh);
  const auto r = run_cli({"draw", mesh, "-o", svg, "--paper", "A5", "--landscape", "--margin", "1cm", "--pen", "0.5",
                          "--png", png, "--size", "160x120"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("on 210x148 mm"), std::string::npos) << r.err;
  const std::string text = read_file(svg);
  EXPECT_NE(text.find(R"(width="210mm" height="148mm" viewBox="0 0 210 148")"), std::string::npos);
  EXPECT_NE(text.find(R"(stroke-width="0.5")"), std::string::npos);
  int layers = 0;
  const std::vector<SvgPath> paths = read_svg_paths(text, layers);
  EXPECT_EQ(layers, 2);
  ASSERT_FALSE(paths.empty());
  double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
  for (const SvgPath& p : paths) {
    EXPECT_GE(p.points.size(), 2u);
    for (size_t i = 0; i < p.points.size(); ++i) {
      const auto [x, y] = p.points[i];
      lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x), lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
      if (i > 0) {
        EXPECT_NE(p.points[i], p.points[i - 1]) << "a point repeated";
      }
    }
  }
  // Inside the margins, and fitted: touching them on one axis (to the 3 decimals written,
  // and a twentieth of the pen, which an extreme point may be dropped by).
  EXPECT_GE(lo_x, 10 - 1e-3);
  EXPECT_LE(hi_x, 200 + 1e-3);
  EXPECT_GE(lo_y, 10 - 1e-3);
  EXPECT_LE(hi_y, 138 + 1e-3);
  EXPECT_TRUE(std::abs(hi_x - lo_x - 190) < 0.03 || std::abs(hi_y - lo_y - 128) < 0.03) << hi_x - lo_x << " " << hi_y - lo_y;
  EXPECT_EQ(read_file(png).substr(1, 3), "PNG");
  // The same input and options, the same bytes.
  const std::string again = (dir / "again.svg").string();
  ASSERT_EQ(run_cli({"draw", mesh, "-o", again, "--paper", "A5", "--landscape", "--margin", "1cm", "--pen", "0.5"}).exit_code, 0);
  EXPECT_EQ(read_file(again), text);
}

// Inkscape, which plotter users send drawings through (the AxiDraw's driver is an
// extension of it), reads a drawing as Meander means it: `inkscape --query-all` lists one
// layer per curve and every path, each inside the sheet (its extents are in px, 96 an inch).
TEST(CliDraw, InkscapeListsALayerPerCurveAndEveryPathOnTheSheet) {
  MEANDER_REQUIRE(std::system("command -v inkscape > /dev/null 2>&1") == 0, "inkscape (Debian inkscape) is not installed");
  const auto dir = output_dir();
  const std::string mesh = (dir / "two.obj").string(), svg = (dir / "two.svg").string();
  write_mesh(test::side_by_side(meander::sphere(800), meander::torus(800), {3, 0, 0}), mesh);
  ASSERT_EQ(run_cli({"draw", mesh, "-o", svg, "--paper", "A5", "--landscape"}).exit_code, 0);
  int layers = 0;
  const size_t paths = read_svg_paths(read_file(svg), layers).size();
  ASSERT_EQ(layers, 2);
  // Inkscape keeps its preferences under HOME: the test's own folder, not the user's.
  const std::string command = "HOME='" + dir.string() + "' inkscape --query-all '" + svg + "' 2> /dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::map<std::string, std::array<double, 4>> objects; // id: x, y, width, height
  char line[512];
  while (std::fgets(line, sizeof line, pipe)) {
    char id[256];
    std::array<double, 4> box{};
    if (std::sscanf(line, "%255[^,],%lf,%lf,%lf,%lf", id, &box[0], &box[1], &box[2], &box[3]) == 5) objects[id] = box;
  }
  ASSERT_EQ(pclose(pipe), 0);
  size_t listed_paths = 0;
  const double px = 96 / 25.4; // px a millimetre
  for (const auto& [id, box] : objects) {
    listed_paths += id.starts_with("path");
    EXPECT_GE(box[0], 0) << id;
    EXPECT_GE(box[1], 0) << id;
    EXPECT_LE(box[0] + box[2], 210 * px) << id;
    EXPECT_LE(box[1] + box[3], 148 * px) << id;
  }
  EXPECT_TRUE(objects.contains("layer1") && objects.contains("layer2")) << objects.size() << " objects";
  EXPECT_EQ(listed_paths, paths);
}

TEST(CliDraw, ACurveFileIsDrawnHiddenByItsOccluder) {
  const auto dir = output_dir();
  const std::string sphere = (dir / "sphere.obj").string(), far = (dir / "far.ply").string(), svg = (dir / "far.svg").string();
  write_mesh(meander::sphere(4000), sphere);
  write_polylines(circle(2, 0.79, -0.6), far);
  auto r = run_cli({"draw", far, "-o", svg, "--view", "front"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(": 1 path "), std::string::npos) << r.err;
  r = run_cli({"draw", far, "--occluder", sphere, "-o", svg, "--view", "front"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(": 0 paths "), std::string::npos) << r.err;
}

// One SVG writer: a curve's SVG is the drawing `meander draw --view front` makes of it.
TEST(CliDraw, ACurvesSvgIsItsDrawingFromTheFront) {
  const auto dir = output_dir();
  const std::string mesh = (dir / "pretzel.obj").string(), curve = (dir / "c.svg").string(), drawn = (dir / "d.svg").string();
  write_mesh(make_shape("pretzel", 3000), mesh);
  ASSERT_EQ(run_cli({"curve", mesh, "-o", curve, "--seed", "5"}).exit_code, 0);
  ASSERT_EQ(run_cli({"draw", mesh, "-o", drawn, "--seed", "5", "--view", "front"}).exit_code, 0);
  const std::string text = read_file(curve);
  EXPECT_EQ(text, read_file(drawn));
  int layers = 0;
  EXPECT_GT(read_svg_paths(text, layers).size(), 1u); // cut where the surface hides it
}

TEST(CliDraw, BadOptionsAreUsageErrorsThatLeaveNoFile) {
  const auto dir = output_dir();
  const std::string mesh = (dir / "s.obj").string(), svg = (dir / "s.svg").string();
  write_mesh(meander::sphere(200), mesh);
  for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
           {"--paper", "50x50", "--margin", "25mm"}, {"--paper", "B7"}, {"--pen", "0"}, {"--margin", "3parsec"}, {"--occluder", mesh}}) {
    std::vector<std::string> args{"draw", mesh, "-o", svg};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << extra[0] << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(svg)) << extra[0];
  }
}

} // namespace
} // namespace meander
