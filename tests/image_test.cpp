// Pictures drawn with one closed line (tone_mesh.h, make_line_picture, `meander image`):
// the quadtree, the line's ink against the picture's tones as an independent renderer
// (rsvg-convert) shows it, and the SVG read back by the test's own parser.
#include "test_support.h"

#include "meander/connectivity.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/render.h"
#include "meander/shapes.h"
#include "meander/textured_io.h"
#include "meander/tone_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <set>
#include <numeric>
#include <string>
#include <vector>

namespace meander {
namespace {

using test::output_dir;
using test::read_file;
using test::read_svg_paths;
using test::run_cli;
using test::SvgPath;

// A w x h picture whose grey level at pixel (x, y) is grey(x, y).
Texture picture(int32_t w, int32_t h, const std::function<uint8_t(int32_t, int32_t)>& grey) {
  Texture t{.width = w, .height = h};
  for (int32_t y = 0; y < h; ++y)
    for (int32_t x = 0; x < w; ++x) {
      const uint8_t g = grey(x, y);
      t.rgba.insert(t.rgba.end(), {g, g, g, 255});
    }
  return t;
}

Texture flat(uint8_t grey) {
  return picture(20, 16, [grey](int32_t, int32_t) { return grey; });
}

// Black on the left, white on the right.
Texture gradient() {
  return picture(400, 300, [](int32_t x, int32_t) { return uint8_t(std::lround(255.0 * x / 399)); });
}

Texture disk() {
  return picture(300, 300, [](int32_t x, int32_t y) { return uint8_t(std::hypot(x - 150, y - 150) < 90 ? 0 : 255); });
}

// "FLH" in bars, black on white.
Texture letters() {
  const int32_t bars[][4] = {{40, 40, 70, 260},   {40, 40, 160, 70},   {40, 135, 140, 165}, {210, 40, 240, 260},
                             {210, 230, 330, 260}, {390, 40, 420, 260}, {510, 40, 540, 260}, {390, 135, 540, 165}};
  return picture(580, 300, [&](int32_t x, int32_t y) {
    for (const auto& b : bars)
      if (x >= b[0] && x < b[2] && y >= b[1] && y < b[3]) return uint8_t(0);
    return uint8_t(255);
  });
}

// A photograph-like scene: a sphere and a torus as Meander renders them, on grey.
Texture scene() {
  Scene s;
  s.meshes.push_back({.mesh = test::side_by_side(meander::sphere(4000), meander::torus(4000), {2.6f, 0, 0})});
  const Image image = render(s, {.width = 400, .height = 260, .view = {.azimuth = 0, .elevation = 35},
                                 .background = {.color = {0.45f, 0.45f, 0.5f}}});
  return {.width = image.width, .height = image.height, .rgba = image.rgba};
}

double length(const Polylines& c) {
  double sum = 0;
  for (int32_t k = 0; k < c.size(); ++k) {
    const auto p = c.polyline(k);
    for (size_t i = 0; i < p.size(); ++i) sum += norm(to_double(p[(i + 1) % p.size()]) - to_double(p[i]));
  }
  return sum;
}

// The gap of the line through a picture: the area it fills over its length.
double gap(const Texture& t, const ToneOptions& tone) {
  const Rect area{.x = 5, .y = 7, .width = 90, .height = 72};
  const CurveResult curve = make_curve(tone_mesh(t, area, tone), CurveJob{});
  EXPECT_EQ(curve.curves.size(), 1);
  return area.width * area.height / length(curve.curves);
}

TEST(ToneMesh, TheLinesInkFollowsTheToneFromTheSpacingInBlackToTheMaxSpacingInWhite) {
  const ToneOptions tone{.spacing = 0.5, .max_spacing = 3};
  EXPECT_NEAR(gap(flat(0), tone), 0.5, 0.5 * 0.05);
  EXPECT_NEAR(gap(flat(255), tone), 3, 3 * 0.05);
  // Between them the ink (the gap's inverse) goes linearly with the darkness, middle
  // tones made of cells of two sizes.
  for (int grey = 16; grey < 255; grey += 16) {
    const double ink = 1 / 3.0 + (1 - grey / 255.0) * (1 / 0.5 - 1 / 3.0);
    EXPECT_NEAR(1 / gap(flat(uint8_t(grey)), tone), ink, 0.05 * ink) << "grey " << grey;
  }
  // Inverted, black is drawn as white was; gamma lightens the middle tones.
  EXPECT_NEAR(gap(flat(0), {.spacing = 0.5, .max_spacing = 3, .invert = true}), 3, 3 * 0.05);
  EXPECT_GT(gap(flat(128), {.spacing = 0.5, .max_spacing = 3, .gamma = 2.2}), 1.2 * gap(flat(128), tone));
}

TEST(ToneMesh, CellsTileTheAreaAsABalancedDisk) {
  const Rect area{.x = 10, .y = 20, .width = 120, .height = 90};
  const PolygonMesh cells = tone_mesh(disk(), area, {.spacing = 0.4, .max_spacing = 6});
  double covered = 0;
  int32_t largest = 0;
  for (int32_t f = 0; f < cells.num_faces(); ++f) {
    const auto face = cells.face(f);
    largest = std::max<int32_t>(largest, int32_t(face.size()));
    for (size_t i = 0; i < face.size(); ++i) { // shoelace; y down, so the corners turn clockwise on paper
      const Vec3 a = cells.positions[size_t(face[i])], b = cells.positions[size_t(face[(i + 1) % face.size()])];
      covered += double(a.x) * b.y - double(b.x) * a.y;
    }
    for (int32_t v : face) {
      const Vec3 p = cells.positions[size_t(v)];
      ASSERT_TRUE(p.x >= 10 - 1e-4 && p.x <= 130 + 1e-4 && p.y >= 20 - 1e-4 && p.y <= 110 + 1e-4);
    }
  }
  EXPECT_NEAR(covered / 2, 120.0 * 90, 1e-2);
  EXPECT_LE(largest, 8); // balanced: at most one midpoint a side
  EXPECT_GE(largest, 5); // and graded: a disk's edge has cells of two sizes side by side
  // A disk: connected (one cycle through it) with V - E + F = 1.
  const Connectivity c = build_connectivity(cells);
  EXPECT_EQ(int64_t(cells.num_vertices()) - c.num_edges() + cells.num_faces(), 1);
  EXPECT_EQ(make_curve(cells, CurveJob{}).curves.size(), 1);
}

TEST(ToneMesh, RefusesOptionsOutOfRange) {
  const Rect area{.width = 100, .height = 100};
  EXPECT_THROW(tone_mesh(disk(), area, {.spacing = 0}), ParameterError);
  EXPECT_THROW(tone_mesh(disk(), area, {.spacing = 2, .max_spacing = 1}), ParameterError);
  EXPECT_THROW(tone_mesh(disk(), area, {.gamma = 0}), ParameterError);
  EXPECT_THROW(tone_mesh(disk(), area, {.spacing = 0.005, .max_spacing = 0.005}), UsageError); // 1.5e8 cells
}


// Whether the segments a-b and c-d share a point.
bool segments_meet(std::array<double, 2> a, std::array<double, 2> b, std::array<double, 2> c, std::array<double, 2> d) {
  const auto orient = [](std::array<double, 2> p, std::array<double, 2> q, std::array<double, 2> r) {
    const double v = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
    return (v > 0) - (v < 0);
  };
  const auto within = [](std::array<double, 2> p, std::array<double, 2> q, std::array<double, 2> r) { // r on p-q's box
    return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) && std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
  };
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) || (o3 == 0 && within(c, d, a)) || (o4 == 0 && within(c, d, b));
}

// The pairs of non-neighbouring segments of a closed path that meet (a grid of 1 mm
// buckets finds the candidates).
int64_t crossings(const SvgPath& path) {
  const auto& p = path.points;
  const size_t n = p.size();
  std::map<std::pair<int, int>, std::vector<size_t>> buckets;
  for (size_t i = 0; i < n; ++i) {
    const auto a = p[i], b = p[(i + 1) % n];
    for (int x = int(std::floor(std::min(a[0], b[0]))); x <= int(std::floor(std::max(a[0], b[0]))); ++x)
      for (int y = int(std::floor(std::min(a[1], b[1]))); y <= int(std::floor(std::max(a[1], b[1]))); ++y) buckets[{x, y}].push_back(i);
  }
  std::set<std::pair<size_t, size_t>> met;
  for (const auto& [cell, segments] : buckets)
    for (size_t u = 0; u < segments.size(); ++u)
      for (size_t v = u + 1; v < segments.size(); ++v) {
        const size_t i = std::min(segments[u], segments[v]), j = std::max(segments[u], segments[v]);
        if (j == i + 1 || (i == 0 && j == n - 1)) continue; // neighbours share their end
        if (segments_meet(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) met.insert({i, j});
      }
  return int64_t(met.size());
}

std::string write_picture(const Texture& t, const std::filesystem::path& path) {
  write_png(Image{.width = t.width, .height = t.height, .rgba = t.rgba}, path);
  return path.string();
}

TEST(CliImage, APictureIsOneClosedPathThatNeverCrossesItselfInsideTheMargins) {
  const auto dir = output_dir();
  const std::string png = write_picture(letters(), dir / "letters.png"), svg = (dir / "letters.svg").string();
  const auto r = run_cli({"image", png, "-o", svg, "--paper", "A5", "--margin", "12mm", "--spacing", "0.5mm", "--seed", "3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("one closed line on 210x148 mm"), std::string::npos) << r.err; // turned to the picture
  const std::string text = read_file(svg);
  EXPECT_NE(text.find(R"(width="210mm" height="148mm" viewBox="0 0 210 148")"), std::string::npos);
  int layers = 0;
  const std::vector<SvgPath> paths = read_svg_paths(text, layers);
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_EQ(layers, 1);
  EXPECT_TRUE(paths[0].closed);
  EXPECT_GT(paths[0].points.size(), 1000u);
  for (const auto& [x, y] : paths[0].points) ASSERT_TRUE(x >= 12 && x <= 198 && y >= 12 && y <= 136) << x << ", " << y;
  EXPECT_EQ(crossings(paths[0]), 0);
  EXPECT_EQ(crossings({.points = {{0, 0}, {1, 1}, {1, 0}, {0, 1}}, .closed = true}), 1); // the check sees a bow tie
}

// A grid of values over 1 mm cells, row by row.
struct Cells {
  int32_t nx = 0, ny = 0;
  std::vector<double> v;
  double& at(int32_t x, int32_t y) { return v[size_t(y) * size_t(nx) + size_t(x)]; }
};

// The mean darkness (1 - luma) of each of the nx x ny cells of an RGBA picture, from the
// pixels whose centres fall inside it.
Cells darkness(const Texture& t, int32_t nx, int32_t ny) {
  Cells c{nx, ny, std::vector<double>(size_t(nx) * size_t(ny))};
  std::vector<int> count(c.v.size());
  for (int32_t y = 0; y < t.height; ++y)
    for (int32_t x = 0; x < t.width; ++x) {
      const uint8_t* p = &t.rgba[(size_t(y) * size_t(t.width) + size_t(x)) * 4];
      const size_t cell = size_t(int32_t((y + 0.5) * ny / t.height)) * size_t(nx) + size_t(int32_t((x + 0.5) * nx / t.width));
      c.v[cell] += 1 - (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255;
      ++count[cell];
    }
  for (size_t i = 0; i < c.v.size(); ++i) c.v[i] /= std::max(count[i], 1);
  return c;
}

// A Gaussian blur of `sigma` cells (edges repeated).
Cells blurred(Cells c, double sigma) {
  const int r = int(std::ceil(3 * sigma));
  std::vector<double> k(size_t(2 * r + 1));
  for (int i = -r; i <= r; ++i) k[size_t(i + r)] = std::exp(-0.5 * i * i / (sigma * sigma));
  const double sum = std::accumulate(k.begin(), k.end(), 0.0);
  for (double& w : k) w /= sum;
  for (int pass = 0; pass < 2; ++pass) {
    Cells out = c;
    for (int32_t y = 0; y < c.ny; ++y)
      for (int32_t x = 0; x < c.nx; ++x) {
        double v = 0;
        for (int i = -r; i <= r; ++i)
          v += k[size_t(i + r)] * (pass == 0 ? c.at(std::clamp(x + i, 0, c.nx - 1), y) : c.at(x, std::clamp(y + i, 0, c.ny - 1)));
        out.at(x, y) = v;
      }
    c = std::move(out);
  }
  return c;
}

double pearson(const Cells& a, const Cells& b) {
  const double n = double(a.v.size());
  const double ma = std::accumulate(a.v.begin(), a.v.end(), 0.0) / n, mb = std::accumulate(b.v.begin(), b.v.end(), 0.0) / n;
  double ab = 0, aa = 0, bb = 0;
  for (size_t i = 0; i < a.v.size(); ++i) {
    ab += (a.v[i] - ma) * (b.v[i] - mb), aa += (a.v[i] - ma) * (a.v[i] - ma), bb += (b.v[i] - mb) * (b.v[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

// Drawn by `meander image` on a 200 mm square sheet with 10 mm margins and rasterised by
// rsvg-convert at 5 pixels a millimetre: the ink over the picture's area in 1 mm cells
// (the picture fills the 180 mm square's width or height, centred), and the picture's
// darkness over the same cells.
std::pair<Cells, Cells> drawn_and_picture(const Texture& t, const std::string& name) {
  const auto dir = output_dir();
  const std::string png = write_picture(t, dir / (name + ".png")), svg = (dir / (name + ".svg")).string();
  const std::string raster = (dir / (name + ".rsvg.png")).string();
  const auto r = run_cli({"image", png, "-o", svg, "--paper", "200x200mm", "--margin", "10mm"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::system(("rsvg-convert --dpi-x 127 --dpi-y 127 -b white -o " + raster + " " + svg).c_str()), 0);
  const Texture drawn = read_texture(raster);
  EXPECT_EQ(drawn.width, 1000);
  const double scale = 180.0 / std::max(t.width, t.height);
  const int32_t nx = int32_t(std::lround(t.width * scale)), ny = int32_t(std::lround(t.height * scale));
  const int32_t x0 = (200 - nx) / 2 * 5, y0 = (200 - ny) / 2 * 5;
  Cells ink{nx, ny, std::vector<double>(size_t(nx) * size_t(ny))};
  for (int32_t y = 0; y < ny * 5; ++y)
    for (int32_t x = 0; x < nx * 5; ++x) {
      const uint8_t* p = &drawn.rgba[(size_t(y0 + y) * size_t(drawn.width) + size_t(x0 + x)) * 4];
      ink.at(x / 5, y / 5) += (1 - (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255) / 25;
    }
  return {ink, darkness(t, nx, ny)};
}

TEST(CliImage, TheDrawingsInkFollowsThePictureAsAnIndependentRendererShowsIt) {
  MEANDER_REQUIRE(std::system("command -v rsvg-convert > /dev/null 2>&1") == 0,
                  "rsvg-convert (Debian librsvg2-bin) is not installed");
  const std::pair<std::string, Texture> pictures[] = {
      {"gradient", gradient()}, {"disk", disk()}, {"letters", letters()}, {"scene", scene()}};
  for (const auto& [name, t] : pictures) {
    const auto [ink, dark] = drawn_and_picture(t, name);
    EXPECT_GE(pearson(blurred(ink, 3), blurred(dark, 3)), 0.85) << name;
    if (name == "gradient") { // black on the left
      double left = 0, right = 0;
      for (int32_t y = 0; y < ink.ny; ++y)
        for (int32_t x = 0; x < ink.nx; ++x) (2 * x < ink.nx ? left : right) += ink.v[size_t(y) * size_t(ink.nx) + size_t(x)];
      EXPECT_GE(left, 2 * right);
    }
  }
}


TEST(CliImage, SameInputSameBytesAndEveryOutputFormat) {
  const auto dir = output_dir();
  const std::string png = write_picture(disk(), dir / "disk.png");
  const auto out = [&](const std::string& name) { return (dir / name).string(); };
  auto r = run_cli({"image", png, "-o", out("a.svg"), "--width", "8cm", "--margin", "5mm", "--duotone", out("a.duo.svg"),
                    "--colors", "red,navy", "--png", out("a.png"), "--size", "300x300"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("on 90x90 mm"), std::string::npos) << r.err; // 80 mm and the margins
  ASSERT_EQ(run_cli({"image", png, "-o", out("b.svg"), "--width", "80", "--margin", "5"}).exit_code, 0);
  EXPECT_EQ(read_file(out("a.svg")), read_file(out("b.svg")));
  ASSERT_EQ(run_cli({"image", png, "-o", out("c.svg"), "--width", "80", "--margin", "5", "--seed", "2"}).exit_code, 0);
  EXPECT_NE(read_file(out("a.svg")), read_file(out("c.svg")));

  // The duotone: the area in the second colour, the inside of the line in the first.
  const std::string duotone = read_file(out("a.duo.svg"));
  EXPECT_NE(duotone.find(R"(<rect x="5" y="5" width="80" height="80" fill="#142148"/>)"), std::string::npos) << duotone.substr(0, 400);
  EXPECT_NE(duotone.find(R"(<path fill="#be2828" fill-rule="evenodd" d="M)"), std::string::npos) << duotone.substr(0, 400);
  const std::string drawing = read_file(out("a.svg"));
  const size_t d = drawing.find(" d=\"");
  ASSERT_NE(d, std::string::npos);
  EXPECT_NE(duotone.find(drawing.substr(d, drawing.find('"', d + 4) - d)), std::string::npos) << "the same line";
  const Texture picture = read_texture(out("a.png"));
  EXPECT_EQ(picture.width, 300);
  EXPECT_EQ(picture.height, 300);

  // The line as a curve file: millimetres, y up.
  ASSERT_EQ(run_cli({"image", png, "-o", out("a.obj"), "--width", "80", "--margin", "5"}).exit_code, 0);
  const Polylines curve = read_polylines(out("a.obj"));
  ASSERT_EQ(curve.size(), 1);
  EXPECT_TRUE(curve.closed(0));
  for (const Vec3& p : curve.points) ASSERT_TRUE(p.x > 5 && p.x < 85 && p.y > 5 && p.y < 85 && p.z == 0);
}

TEST(CliImage, BadPicturesAndOptionsAreClearErrorsThatLeaveNoFile) {
  const auto dir = output_dir();
  const std::string png = write_picture(gradient(), dir / "gradient.png"), svg = (dir / "out.svg").string();
  const std::string tiny = write_picture(picture(1, 1, [](int32_t, int32_t) { return uint8_t(0); }), dir / "tiny.png");
  const std::string text = test::write_file("text.png", "not a picture").string(), empty = test::write_file("empty.png", "").string();
  struct Case {
    std::vector<std::string> args;
    int exit_code;
    std::string says;
  };
  const Case cases[] = {
      {{text}, 1, "text.png: cannot decode image"},
      {{empty}, 1, "empty.png: file is empty"},
      {{(dir / "missing.png").string()}, 1, "missing.png: cannot open"},
      {{tiny}, 1, "tiny.png: a picture of 1x1 pixels has no tones to draw"},
      {{png, "--max-pixels", "1000"}, 1, "gradient.png: 400x300 pixels, more than the 1000 allowed"},
      {{png, "--paper", "50x50", "--margin", "25mm"}, 2, "no room inside margins"},
      {{png, "--spacing", "2", "--max-spacing", "1"}, 2, "--max-spacing must be at least the spacing"},
      {{png, "--spacing", "3parsec"}, 2, "--spacing: unknown unit 'parsec'"},
      {{png, "--gamma", "0"}, 2, "--gamma: expected a number in [0.1, 10]"},
      {{png, "--paper", "B7"}, 2, "--paper: paper 'B7'"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"image", c.args[0], "-o", svg};
    args.insert(args.end(), c.args.begin() + 1, c.args.end());
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.says << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(svg)) << c.says;
  }
}

} // namespace
} // namespace meander
