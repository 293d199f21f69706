// `meander duotone` as a user runs it: the files it writes open as what they claim
// (OBJ + MTL + PNG with relative paths, GLB the Khronos validator accepts, binary PLY
// regions, closed curves), and bad requests are refused precisely without output.
#include "gltf_validator.h"
#include "test_support.h"

#include "meander/check.h"
#include "meander/connectivity.h"
#include "meander/io.h"
#include "meander/remesh.h"
#include "meander/textured_io.h"

#include <gmock/gmock.h>

#include <string>

namespace meander::test {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

TEST(CliDuotone, ObjWithMtlAndTextureCurveAndRegions) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const fs::path dir = output_dir();
  const CommandResult r = run_cli({"duotone", (shared_meshes() / "eight.off").string(), "-o", (dir / "eight.obj").string(),
                                   "--curve", (dir / "curve.obj").string(), "--regions",
                                   (dir / "a.ply").string() + "," + (dir / "b.ply").string(), "--texture-size", "256"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("2 colour regions and 1 separating curve"));
  // Relative paths, so the three files can move together.
  EXPECT_THAT(read_file(dir / "eight.obj"), HasSubstr("mtllib eight.mtl"));
  EXPECT_THAT(read_file(dir / "eight.mtl"), HasSubstr("map_Kd eight_texture.png"));
  const TexturedMesh surface = read_textured_mesh(dir / "eight.obj");
  ASSERT_EQ(surface.appearance.materials.size(), 1u);
  EXPECT_EQ(surface.appearance.materials[0].texture.width, 256);

  const Polylines curve = read_polylines(dir / "curve.obj");
  ASSERT_EQ(curve.size(), 1);
  EXPECT_TRUE(curve.closed(0));
  EXPECT_THAT(read_file(dir / "a.ply"), HasSubstr("format binary_little_endian"));
  const PolygonMesh a = read_mesh(dir / "a.ply"), b = read_mesh(dir / "b.ply");
  for (const PolygonMesh* piece : {&a, &b}) {
    const MeshReport report = inspect(*piece);
    EXPECT_EQ(report.non_manifold_edges, 0);
    EXPECT_EQ(report.non_manifold_vertices, 0);
    EXPECT_EQ(report.boundary_loops, 1); // the curve
    EXPECT_EQ(report.components.size(), 1u);
  }
  EXPECT_NEAR(surface_area(a) + surface_area(b), surface_area(surface.mesh), 1e-4 * surface_area(surface.mesh));
}

TEST(CliDuotone, GlbPassesTheKhronosValidatorPlainAndSubdivided) {
  MEANDER_REQUIRE_SHARED_MESHES();
  MEANDER_REQUIRE(gltf_validator_installed(),
                  "glTF validator not installed: run `npm ci` in tests/ (make test does) with node on the PATH");
  const fs::path dir = output_dir();
  for (const std::vector<std::string>& extra : {std::vector<std::string>{"--tiles", "stripes"},
                                                 std::vector<std::string>{"--subdivide", "2", "--quad", "dual-simplest"},
                                                 std::vector<std::string>{"--rule", "flip", "--tiles", "dots"}}) {
    std::vector<std::string> args = {"duotone", (shared_meshes() / "bob_small.ply").string(), "-o", (dir / "bob.glb").string(),
                                     "--texture-size", "128"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CommandResult r = run_cli(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json report = gltf_validator_report(dir / "bob.glb");
    ASSERT_TRUE(report.is_object());
    EXPECT_EQ(report["numErrors"], 0) << extra[0] << ": " << report["messages"].dump(1);
    EXPECT_FALSE(read_textured_mesh(dir / "bob.glb").appearance.texcoords.empty());
  }
}

TEST(CliDuotone, ABoundaryFallsBackToDualSimplestWithANote) {
  const fs::path dir = output_dir();
  ASSERT_EQ(run_cli({"generate", "grid", "-o", (dir / "grid.obj").string(), "--faces", "50"}).exit_code, 0);
  const CommandResult r = run_cli({"duotone", (dir / "grid.obj").string(), "-o", (dir / "out.glb").string(), "--texture-size", "64"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("grid.obj: note: the mesh has 20 boundary edges: Catmull-Clark quads would alternate colours"));
  EXPECT_THAT(r.err, HasSubstr("quads (dual-simplest), 2 colour regions and 1 separating curve"));
}

TEST(CliDuotone, PictureOfTheTexturedSurface) {
  const fs::path dir = output_dir();
  ASSERT_EQ(run_cli({"generate", "torus", "-o", (dir / "torus.obj").string(), "--faces", "200"}).exit_code, 0);
  const CommandResult r = run_cli({"duotone", (dir / "torus.obj").string(), "-o", (dir / "out.obj").string(), "--png",
                                   (dir / "out.png").string(), "--size", "160x120", "--texture-size", "128", "--tiles", "outline"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture png = read_texture(dir / "out.png");
  EXPECT_EQ(png.width, 160);
  EXPECT_EQ(png.height, 120);
}

// Each refusal: its exit code, the words that say what is wrong, and no file written
// (into a folder of its own, emptied first).
void expect_refused(const std::vector<std::string>& extra, int exit_code, const std::string& words, const fs::path& input) {
  const fs::path dir = input.parent_path() / "out";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<std::string> args = {"duotone", input.string(), "-o", (dir / "out.obj").string(), "--curve", (dir / "c.obj").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const CommandResult r = run_cli(args);
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_THAT(r.err, HasSubstr(words));
  EXPECT_TRUE(fs::is_empty(dir)) << words;
}

TEST(CliDuotone, RefusesBadRequestsPreciselyWithoutOutput) {
  const fs::path quads = write_file("torus5x6.obj", [] {
    // A closed torus of 5 x 6 quads: the 5 around make an odd cycle.
    std::string obj;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 6; ++j) {
        const double a = 2 * M_PI * i / 5, b = 2 * M_PI * j / 6;
        obj += "v " + std::to_string((1 + 0.4 * std::cos(b)) * std::cos(a)) + " " + std::to_string((1 + 0.4 * std::cos(b)) * std::sin(a)) +
               " " + std::to_string(0.4 * std::sin(b)) + "\n";
      }
    auto id = [](int i, int j) { return std::to_string(((i + 5) % 5) * 6 + (j + 6) % 6 + 1); };
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 6; ++j) obj += "f " + id(i, j) + " " + id(i + 1, j) + " " + id(i + 1, j + 1) + " " + id(i, j + 1) + "\n";
    return obj;
  }());
  expect_refused({"--colors", "red,#12g456"}, 2, "--colors 'red,#12g456': '#12g456' is not a colour", quads);
  expect_refused({"--colors", "navy,navy"}, 2, "the two colours are the same", quads);
  expect_refused({"--tiles", "zigzag"}, 2, "--tiles: unknown value 'zigzag' (expected truchet, outline, triangles, stripes or dots)", quads);
  expect_refused({"--texture-size", "99"}, 2, "--texture-size 99: expected an even number of pixels in 64..8192", quads);
  expect_refused({"--regions", "only.ply"}, 2, "--regions 'only.ply': expected two files A.ply,B.ply", quads);
  expect_refused({"--quad", "none"}, 1, "would need both colours (an odd cycle of edges runs through it)", quads);
}

} // namespace
} // namespace meander::test
