// Textured meshes in pictures: each texel colour of the checker quad lands in its own
// quadrant, from the library and from `meander render` with OBJ + MTL and with GLB; bad
// material files are refused with the file and line, exit code 1 and no picture.
#include "meander/error.h"
#include "meander/io.h"
#include "meander/textured_io.h"
#include "meander/render.h"
#include "checker_quad.h"
#include "test_support.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace meander {
namespace {

namespace fs = std::filesystem;
using test::checker_quad;
using test::checker_colors;
using test::output_dir;
using test::run_cli;
using test::write_file;

constexpr int width = 160, height = 120;

// The checker colour nearest in hue to pixel (x, y): shading scales a colour but keeps
// its proportions, so colours are compared as fractions of their sum.
int nearest_checker_color(const uint8_t* pixels, int x, int y) {
  const uint8_t* p = &pixels[(size_t(y) * width + x) * 4];
  auto hue = [](double r, double g, double b) {
    const double sum = r + g + b + 1e-9;
    return std::array<double, 3>{r / sum, g / sum, b / sum};
  };
  const auto seen = hue(p[0], p[1], p[2]);
  int best = -1;
  double best_distance = 1e9;
  for (int k = 0; k < 4; ++k) {
    const auto c = hue(checker_colors[k][0], checker_colors[k][1], checker_colors[k][2]);
    const double d = std::pow(seen[0] - c[0], 2) + std::pow(seen[1] - c[1], 2) + std::pow(seen[2] - c[2], 2);
    if (d < best_distance) best = k, best_distance = d;
  }
  return best;
}

// From the front, the quad fills the middle of the picture (88% of its height): the
// centre of each quadrant of the quad shows one texel, red top left to yellow bottom right.
void expect_checker_quadrants(const std::vector<uint8_t>& rgba) {
  ASSERT_EQ(rgba.size(), size_t(width) * height * 4);
  const int dx = int(0.22 * height), dy = int(0.22 * height);
  const int cx = width / 2, cy = height / 2;
  EXPECT_EQ(nearest_checker_color(rgba.data(), cx - dx, cy - dy), 0) << "top left";
  EXPECT_EQ(nearest_checker_color(rgba.data(), cx + dx, cy - dy), 1) << "top right";
  EXPECT_EQ(nearest_checker_color(rgba.data(), cx - dx, cy + dy), 2) << "bottom left";
  EXPECT_EQ(nearest_checker_color(rgba.data(), cx + dx, cy + dy), 3) << "bottom right";
}

TEST(TexturedRender, EachTexelColourLandsInItsQuadrant) {
  TexturedMesh quad = checker_quad();
  Scene scene;
  scene.meshes.push_back({.mesh = std::move(quad.mesh), .appearance = std::move(quad.appearance)});
  const Image image = render(scene, {.width = width, .height = height, .view = parse_view("front"), .samples = 2});
  expect_checker_quadrants(image.rgba);
  write_png(image, output_dir() / "quad.png");
}

TEST(TexturedRender, RefusesAnAppearanceThatDoesNotFitTheMesh) {
  TexturedMesh quad = checker_quad();
  quad.appearance.texcoords.resize(2);
  Scene scene;
  scene.meshes.push_back({.mesh = std::move(quad.mesh), .appearance = std::move(quad.appearance)});
  EXPECT_THROW(render(scene, {.width = width, .height = height}), UsageError);
}

TEST(TexturedRender, CliRendersObjWithMtlAndGlb) {
  const fs::path dir = output_dir();
  write_textured_mesh(checker_quad(), dir / "quad.obj");
  write_textured_mesh(checker_quad(), dir / "quad.glb");
  for (const char* input : {"quad.obj", "quad.glb"}) {
    const fs::path png = dir / (std::string(input) + ".png");
    const auto r = run_cli({"render", (dir / input).string(), "-o", png.string(), "--view", "front", "--size", "160x120"});
    ASSERT_EQ(r.exit_code, 0) << input << ": " << r.err;
    expect_checker_quadrants(read_texture(png).rgba);
  }
}

// Each bad input: exit code 1, the precise message, and no picture.
class TexturedRenderCliRefuses : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = output_dir();
    write_textured_mesh(checker_quad(), dir_ / "quad.obj");
  }
  void expect_refused(const fs::path& obj, const std::string& message) {
    const fs::path png = dir_ / "out.png";
    const auto r = run_cli({"render", obj.string(), "-o", png.string()});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "meander: " + message + "\n");
    EXPECT_FALSE(fs::exists(png));
  }
  fs::path dir_;
};

TEST_F(TexturedRenderCliRefuses, AMissingTextureFile) {
  fs::remove(dir_ / "quad_texture.png");
  expect_refused(dir_ / "quad.obj", (dir_ / "quad.mtl").string() + ":3: map_Kd 'quad_texture.png': " +
                                        (dir_ / "quad_texture.png").string() + ": cannot open: No such file or directory");
}

TEST_F(TexturedRenderCliRefuses, AnUnreadableMtl) {
  // A folder where the MTL should be: it exists but cannot be read as a file.
  fs::remove(dir_ / "quad.mtl");
  fs::create_directory(dir_ / "quad.mtl");
  expect_refused(dir_ / "quad.obj",
                 (dir_ / "quad.obj").string() + ":1: mtllib 'quad.mtl': " + (dir_ / "quad.mtl").string() + ": is a directory");
}

TEST_F(TexturedRenderCliRefuses, AMalformedMtl) {
  write_file("quad.mtl", "newmtl checker\nKd 1 1\n");
  expect_refused(dir_ / "quad.obj", (dir_ / "quad.obj").string() + ":1: mtllib 'quad.mtl': " + (dir_ / "quad.mtl").string() +
                                        ":2: missing Kd value");
}

TEST_F(TexturedRenderCliRefuses, AMissingMtllibTarget) {
  fs::remove(dir_ / "quad.mtl");
  expect_refused(dir_ / "quad.obj", (dir_ / "quad.obj").string() + ":1: mtllib 'quad.mtl': " + (dir_ / "quad.mtl").string() +
                                        ": cannot open: No such file or directory");
}

} // namespace
} // namespace meander
