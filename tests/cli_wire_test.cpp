// `meander wire` as a user runs it on real meshes, its output judged by CGAL: closed,
// outward, positive volume and free of self-intersection at the default sizes.
#include "cgal_judge.h"
#include "test_support.h"

#include "meander/check.h"
#include "meander/io.h"
#include "meander/shapes.h"

#include <nlohmann/json.hpp>

#include <set>
#include <string>

namespace meander::test {
namespace {

// Small and medium meshes of every trait: genus 0 to 3, quads and n-gons, boundary,
// several components, non-orientable, and ones that need repair.
const char* const wire_meshes[] = {"tetrahedron.obj", "beveledcube.obj",   "genus3hexa1.obj", "eight.off",
                                   "bob_small.ply",   "fandisk_quads.off", "moebius.obj",     "platonic_shelf.obj",
                                   "grid.off",        "spot_control_mesh.obj", "hourglass_ico.obj", "degtri_four.off"};

class CliWire : public ::testing::TestWithParam<const char*> {};

void expect_printable_tori(const std::filesystem::path& wire, const std::filesystem::path& report_path, int cycles,
                           bool clear = true) {
  const nlohmann::json report = nlohmann::json::parse(read_file(report_path));
  EXPECT_TRUE(report["watertight"].get<bool>());
  if (clear) {
    EXPECT_FALSE(report["self_intersecting"].get<bool>());
  }
  ASSERT_EQ(int(report["components"].size()), cycles);
  for (const auto& c : report["components"]) EXPECT_EQ(c["euler_characteristic"].get<int>(), 0);
  const CgalVerdict cgal = cgal_judge(read_mesh(wire));
  ASSERT_TRUE(cgal.loaded);
  EXPECT_TRUE(cgal.closed);
  EXPECT_EQ(cgal.self_intersecting, report["self_intersecting"].get<bool>());
  EXPECT_GT(cgal.volume, 0);
  EXPECT_TRUE(cgal.outward);
}

// One wire per connected component of the repaired mesh.
int cycles_of(const std::filesystem::path& mesh) {
  return int(inspect(repair(read_mesh(mesh), mesh.string()).mesh).components.size());
}

TEST_P(CliWire, ConstantWireAtAutoRadiusIsPrintable) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto mesh = shared_meshes() / GetParam();
  const auto dir = output_dir();
  const CommandResult r = run_cli({"wire", mesh.string(), "-o", (dir / "wire.stl").string(), "--samples", "2", "--report", (dir / "report.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("(auto)"), std::string::npos) << r.err;
  expect_printable_tori(dir / "wire.stl", dir / "report.json", cycles_of(mesh));
}

TEST_P(CliWire, VariableWireIsPrintable) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto mesh = shared_meshes() / GetParam();
  const auto dir = output_dir();
  const CommandResult r = run_cli({"wire", mesh.string(), "-o", (dir / "wire.ply").string(), "--method", "variable", "--levels", "1", "--report", (dir / "report.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Known limit (docs/wires.md): Spot's 180-face control mesh crosses itself (its own
  // triangles do), and a wire that follows it cannot be clear there; the report must
  // still say so, CGAL agreeing, and the summary say why. The beveled cube and fandisk
  // left this list with the shaped tree, bob_small when each trapezoid's slab took one
  // normal, genus3hexa1 (slabs folding across right-angled creases) with the clearing
  // rounds.
  const bool crossing_surface = std::string(GetParam()) == "spot_control_mesh.obj";
  expect_printable_tori(dir / "wire.ply", dir / "report.json", cycles_of(mesh), !crossing_surface);
  EXPECT_EQ(r.err.find("the surface itself crosses itself") != std::string::npos, crossing_surface) << r.err;
}

TEST_P(CliWire, RibbonsAreBands) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto mesh = shared_meshes() / GetParam();
  const auto dir = output_dir();
  for (const char* method : {"constant", "variable"}) {
    const CommandResult r = run_cli({"wire", mesh.string(), "-o", (dir / "ribbon.obj").string(), "--method", method, "--shape", "ribbon",
                                     "--samples", "2", "--levels", "1", "--report", (dir / "ribbon.json").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const MeshReport ribbon = inspect(read_mesh(dir / "ribbon.obj"));
    EXPECT_EQ(ribbon.non_manifold_edges, 0) << method;
    EXPECT_EQ(ribbon.boundary_loops, 2 * cycles_of(mesh)) << method;
    // The variable ribbon's control strip lies in the cycle's triangles, so it stays
    // clear even where the slab of a wire folds; smoothing a fold on Spot's coarse
    // control mesh makes a few smoothed triangles touch (docs/wires.md).
    if (std::string(method) == "variable" && std::string(GetParam()) != "spot_control_mesh.obj") {
      EXPECT_FALSE(nlohmann::json::parse(read_file(dir / "ribbon.json"))["self_intersecting"].get<bool>());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, CliWire, ::testing::ValuesIn(wire_meshes),
                         [](const ::testing::TestParamInfo<const char*>& mesh) { return test_name(mesh.param); });

// At the default two levels of smoothing the limit surface of a connector between two
// slabs bent by the tetrahedron's edges folds unless the slabs thin out there, the
// beveled cube's rectangles make slivers, which the shaped tree avoids, and genus3hexa1's
// warped hexagons made flat triangles around their centroids, at six seeds of eight,
// until they were split into stars of triangles; the variable method builds on the
// shaped tree unless --tree says otherwise.
TEST(CliWireOutput, VariableWireAtDefaultLevelsOnCoarseMeshes) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  for (const auto& [name, seed] : {std::pair{"tetrahedron.obj", "1"}, {"beveledcube.obj", "1"}, {"genus3hexa1.obj", "1"},
                                   {"genus3hexa1.obj", "3"}, {"genus3hexa1.obj", "5"}}) {
    const auto mesh = (shared_meshes() / name).string();
    const CommandResult r = run_cli({"wire", mesh, "-o", (dir / "wire.ply").string(), "--method", "variable", "--seed", seed,
                                     "--report", (dir / "report.json").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    SCOPED_TRACE(std::string(name) + " seed " + seed);
    expect_printable_tori(dir / "wire.ply", dir / "report.json", 1);
  }
  const auto cube = (shared_meshes() / "beveledcube.obj").string();
  for (const char* tree : {"", "shaped", "random"}) {
    std::vector<std::string> args = {"wire", cube, "-o", (dir / (std::string(tree) + "cube.ply")).string(), "--method", "variable", "--levels", "0"};
    if (*tree) args.insert(args.end(), {"--tree", tree});
    const CommandResult t = run_cli(args);
    ASSERT_EQ(t.exit_code, 0) << t.err;
  }
  EXPECT_TRUE(read_file(dir / "cube.ply") == read_file(dir / "shapedcube.ply"));
  EXPECT_FALSE(read_file(dir / "cube.ply") == read_file(dir / "randomcube.ply"));
}

// A scan's sharp crease at the default sizes: the cut of the camel's neck, where a wall
// of long thin triangles meets the neck (camelhead.off at level 2 crossed itself at
// every seed before each slab's normal was kept within 45 degrees of its triangle's;
// the whole head takes a minute, so a piece of it is cut out here).
TEST(CliWireOutput, VariableWireIsClearAcrossTheSharpCreaseOfAScan) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  write_mesh(crop(read_mesh(shared_meshes() / "camelhead.off"), {0.1547f, 0.0597f, -0.4352f}, 0.05), dir / "neck.obj");
  const CommandResult r = run_cli({"wire", (dir / "neck.obj").string(), "-o", (dir / "wire.stl").string(), "--method", "variable",
                                   "--report", (dir / "report.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_printable_tori(dir / "wire.stl", dir / "report.json", 1);
}

// `--method variable` flips the long edges of caps first and says so; --cap-angle 180
// or --keep-faces keeps them, and the constant method never flips.
TEST(CliWireOutput, VariableMethodFlipsCapsUnlessTold) {
  const auto dir = output_dir();
  const auto cap = write_file("cap.obj", "v 0 0 0\nv 2 0 0\nv 1 0.05 0\nv 1 -1 0\nf 1 2 3\nf 2 1 4\n");
  auto wire = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args = {"wire", cap.string(), "-o", (dir / out).string(), "--levels", "0", "--samples", "2"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args);
  };
  const CommandResult flipped = wire("flipped.ply", {"--method", "variable"});
  ASSERT_EQ(flipped.exit_code, 0) << flipped.err;
  EXPECT_NE(flipped.err.find("cap.obj: note: flipped 1 edge facing an angle over 120 degrees, where the slabs would fold"),
            std::string::npos)
      << flipped.err;
  for (const char* keep : {"--cap-angle=180", "--keep-faces"}) {
    const CommandResult kept = wire("kept.ply", {"--method", "variable", keep});
    ASSERT_EQ(kept.exit_code, 0) << kept.err;
    EXPECT_EQ(kept.err.find("flipped"), std::string::npos) << kept.err;
    EXPECT_FALSE(read_file(dir / "flipped.ply") == read_file(dir / "kept.ply"));
  }
  const CommandResult constant = wire("constant.ply", {});
  ASSERT_EQ(constant.exit_code, 0) << constant.err;
  EXPECT_EQ(constant.err.find("flipped"), std::string::npos) << constant.err;
  const CommandResult bad = wire("bad.ply", {"--method", "variable", "--cap-angle", "80"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--cap-angle"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.ply"));
}

// `--method variable` also collapses the short edges of needles, and says so;
// --keep-faces keeps them.
TEST(CliWireOutput, VariableMethodCollapsesNeedlesUnlessTold) {
  const auto dir = output_dir();
  PolygonMesh mesh = grid(18); // 3 x 3 squares; vertex 5 is (1, 1) in cells, 6 is (2, 1)
  mesh.positions[5] = mesh.positions[6] * 0.99f + mesh.positions[5] * 0.01f;
  write_mesh(mesh, dir / "needles.obj");
  auto wire = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args = {"wire", (dir / "needles.obj").string(), "-o", (dir / out).string(), "--method", "variable", "--levels", "0"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args);
  };
  const CommandResult collapsed = wire("collapsed.ply", {});
  ASSERT_EQ(collapsed.exit_code, 0) << collapsed.err;
  // (The vertex moved also makes two caps, which are flipped first.)
  EXPECT_NE(collapsed.err.find("needles.obj: note: flipped 2 edges facing an angle over 120 degrees and collapsed 1 short edge of "
                               "needles (an angle under 5 degrees) or of triangles folded over their neighbours, where the slabs would fold"),
            std::string::npos)
      << collapsed.err;
  const CommandResult kept = wire("kept.ply", {"--keep-faces"});
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_EQ(kept.err.find("collapsed"), std::string::npos) << kept.err;
}

// Section 4.1: with s and t near 1 the variable ribbons cover the surface densely
// without running into each other (on meshes without long thin faces).
TEST(CliWireOutput, DenseRibbonsDoNotSelfIntersect) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  for (const char* mesh : {"sphere.obj", "eight.off"}) {
    const CommandResult r = run_cli({"wire", (shared_meshes() / mesh).string(), "-o", (dir / "ribbon.ply").string(), "--method",
                                     "variable", "--shape", "ribbon", "--s", "0.95", "--t", "0.95", "--report", (dir / "r.json").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(nlohmann::json::parse(read_file(dir / "r.json"))["self_intersecting"].get<bool>()) << mesh;
    const CgalVerdict cgal = cgal_judge(read_mesh(dir / "ribbon.ply"));
    ASSERT_TRUE(cgal.loaded) << mesh;
    EXPECT_FALSE(cgal.self_intersecting) << mesh;
  }
}

TEST(CliWireOutput, EveryFormatIsWritten) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  for (const char* ext : {".stl", ".ply", ".obj", ".off", ".3mf", ".glb"}) {
    const auto out = dir / (std::string("wire") + ext);
    const CommandResult r = run_cli({"wire", (shared_meshes() / "tetrahedron.obj").string(), "-o", out.string(), "--samples", "1", "--sides", "4"});
    ASSERT_EQ(r.exit_code, 0) << ext << ": " << r.err;
    EXPECT_GT(std::filesystem::file_size(out), 0u) << ext;
    if (std::string(ext) != ".3mf") { // written by lib3mf, not read back by Meander
      EXPECT_GT(read_mesh(out).num_faces(), 0) << ext;
    }
  }
}

// --png renders the result in one step, with the picture options of `render`.
TEST(CliWireOutput, PngOfTheResult) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  const std::string mesh = (shared_meshes() / "tetrahedron.obj").string();
  for (const char* shape : {"wire", "ribbon"}) {
    const auto png = dir / (std::string(shape) + ".png");
    const CommandResult r = run_cli({"wire", mesh, "-o", (dir / "w.stl").string(), "--shape", shape, "--samples", "1",
                                     "--png", png.string(), "--size", "120x90"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_file(png).substr(1, 3), "PNG") << shape;
  }
  const CommandResult r = run_cli({"wire", mesh, "-o", (dir / "w.stl").string(), "--samples", "1", "--png",
                                   (dir / "spin.png").string(), "--size", "60x40", "--turntable", "3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* frame : {"spin_000.png", "spin_001.png", "spin_002.png"}) EXPECT_TRUE(std::filesystem::exists(dir / frame));
  // A bad picture option is refused before any work: no mesh either.
  const CommandResult bad = run_cli({"wire", mesh, "-o", (dir / "none.stl").string(), "--png", (dir / "x.png").string(), "--view", "sideways"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "none.stl"));
}

// A ribbon is searched too, and narrowed about its middle where it crosses itself, a few
// rounds: on the connecting rod's CAD slivers the ribbon at level 0 had 9 crossing faces
// before (its surface crosses itself elsewhere, which the ribbon at s = 0.6 keeps clear
// of), and is clear after, CGAL agreeing.
TEST(CliWireOutput, RibbonsAreNarrowedWhereTheyCross) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  const CommandResult r = run_cli({"wire", (shared_meshes() / "conrod.stl").string(), "-o", (dir / "ribbon.ply").string(),
                                   "--method", "variable", "--shape", "ribbon", "--levels", "0", "--report",
                                   (dir / "r.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(nlohmann::json::parse(read_file(dir / "r.json"))["self_intersecting"].get<bool>());
  const CgalVerdict cgal = cgal_judge(read_mesh(dir / "ribbon.ply"));
  ASSERT_TRUE(cgal.loaded);
  EXPECT_FALSE(cgal.self_intersecting);
}

// --min-thickness judges the wire's minimum thickness in the report and the summary; the
// wire is written either way, and the command succeeds: the report is the verdict.
TEST(CliWireOutput, MinimumThicknessIsJudged) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  const std::string mesh = (shared_meshes() / "tetrahedron.obj").string();
  const auto report = dir / "report.json";
  for (const double required : {1e-4, 10.0}) {
    const CommandResult r = run_cli({"wire", mesh, "-o", (dir / "wire.stl").string(), "--samples", "1", "--min-thickness",
                                     std::to_string(required), "--report", report.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json json = nlohmann::json::parse(read_file(report));
    const bool thin = required > json["min_thickness"].get<double>();
    EXPECT_EQ(json["too_thin"].get<bool>(), thin) << required;
    EXPECT_EQ(json["printable"].get<bool>(), !thin) << required;
    EXPECT_NE(r.err.find(thin ? "thinner than the 10 required" : "at least the 0.0001 required"), std::string::npos) << r.err;
  }
  const CommandResult ribbon = run_cli({"wire", mesh, "-o", (dir / "ribbon.stl").string(), "--shape", "ribbon",
                                        "--min-thickness", "1"});
  EXPECT_EQ(ribbon.exit_code, 2);
  EXPECT_NE(ribbon.err.find("--min-thickness applies to wires"), std::string::npos) << ribbon.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "ribbon.stl"));
  const CommandResult info = run_cli({"info", (dir / "wire.stl").string(), "--solid", "--min-thickness", "10"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("thinner than the 10 required"), std::string::npos) << info.out;
}

// A wire too large for the machine's memory is refused before it is made (the kernel
// would kill the process after minutes otherwise), naming the --levels that fits: a 12k
// face sphere at 6 levels would be 2.4 billion triangles, more than any test machine
// holds. So is a duotone surface.
TEST(CliWireOutput, TooLargeForMemoryIsRefusedUpFront) {
  const auto dir = output_dir();
  const auto mesh = dir / "sphere.ply";
  ASSERT_EQ(run_cli({"generate", "sphere", "--faces", "12000", "-o", mesh.string()}).exit_code, 0);
  const auto out = dir / "wire.ply";
  const CommandResult r = run_cli({"wire", mesh.string(), "-o", out.string(), "--method", "variable", "--levels", "6"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the variable wire would have"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("of memory, and this machine has"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("use --levels "), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // The same for a duotone surface subdivided 5 times: 300,000 quads become 300 million.
  const auto large = dir / "large.ply";
  ASSERT_EQ(run_cli({"generate", "sphere", "--faces", "100000", "-o", large.string()}).exit_code, 0);
  const auto textured = dir / "duotone.obj";
  const CommandResult d = run_cli({"duotone", large.string(), "-o", textured.string(), "--subdivide", "5"});
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("the duotone surface at --subdivide 5 would have"), std::string::npos) << d.err;
  EXPECT_NE(d.err.find("of memory, and this machine has"), std::string::npos) << d.err;
  EXPECT_FALSE(std::filesystem::exists(textured));
}

// Bad parameters are usage errors (exit 2) named on stderr, and nothing is written.
TEST(CliWireOutput, BadParametersAreRefused) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  const std::string mesh = (shared_meshes() / "tetrahedron.obj").string(), out = (dir / "wire.stl").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--radius", "-1"}, "--radius: expected a positive number or auto, got -1"},
      {{"--radius", "wide"}, "--radius: expected a positive number or auto, got wide"},
      {{"--sides", "2"}, "--sides"},
      {{"--method", "variable", "--s", "1.5"}, "--s"},
      {{"--method", "variable", "--t", "-0.5"}, "--t"},
      {{"--method", "variable", "--thickness", "-1"}, "--thickness"},
      {{"--shape", "tube"}, "--shape"},
      {{"--min-thickness", "-0.4"}, "--min-thickness"},
  };
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"wire", mesh, "-o", out};
    args.insert(args.end(), extra.begin(), extra.end());
    const CommandResult r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << message;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << message;
  }
  const CommandResult r = run_cli({"wire", mesh, "-o", (dir / "wire.xyz").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unsupported extension '.xyz'"), std::string::npos) << r.err;
}

} // namespace
} // namespace meander::test
