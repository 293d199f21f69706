// `meander curve` and `meander info` as a user runs them, on every real mesh and on
// generated shapes, judged by the independent certificate checker.
#include "certificate.h"
#include "test_support.h"

#include "meander/io.h"

#include <fstream>
#include <sstream>

namespace meander::test {
namespace {

struct RealMesh {
  const char* file;
  int components;   // cycles expected after repair; -1: not stated by INDEX.md
  long triangles;   // 2E - boundary edges from INDEX.md; -1: changed by repair
  bool needs_repair;
};

// Facts from ../shared/meshes/INDEX.md, grouped by trait.
const RealMesh real_meshes[] = {
    // closed, genus 0 .. 4
    {"bunny_closed.off", 1, 2 * 104499, false},
    {"spot_triangulated.obj", 1, 2 * 8784, false},
    {"spot_quadrangulated.obj", 1, 2 * 5856, false},
    {"spot_control_mesh.obj", 1, 2 * 366, false},
    {"tetrahedron.obj", 1, 2 * 6, false},
    {"icosahedron_binary.stl", 1, 2 * 30, false},
    {"sphere.obj", 1, 2 * 1920, false},
    {"torus.obj", 1, 2 * 6912, false},
    {"kitten.off", 1, 2 * 30000, false},
    {"bob_small.ply", 1, 2 * 750, false},
    {"eight.off", 1, 2 * 2304, false},
    {"genus3hexa1.obj", 1, 2 * 247, false},
    {"fertility.off", 1, 2 * 13500, false},
    {"fandisk_quads.off", 1, 2 * 1528, false},
    // open
    {"stanford-bunny_original_holes.obj", 1, 2 * 104288 - 223, true}, // 1113 unreferenced vertices
    {"face.obj", 1, 2 * 77616 - 96, false},
    {"grid.off", 1, 2 * 400 - 32, false},
    {"camelhead.off", 1, 2 * 34084 - 56, false},
    {"degtri_four.off", 1, 2 * 8 - 4, false}, // zero-area face kept
    {"moebius.obj", 1, 2 * 504 - 112, false}, // non-orientable: a note, not a repair
    // several components
    {"platonic_shelf.obj", 5, 2 * 90, false},
    // broken: repaired
    {"hourglass_ico.obj", 2, 2 * 60, true},   // the pinch vertex is split: two icosahedra
    {"triple_vierbein.obj", -1, -1, true},    // non-manifold edges are cut
    {"conrod.stl", -1, -1, true},             // misoriented faces, non-manifold edges
    {"beveledcube.obj", 1, 2 * 48, true},     // 4 faces re-oriented
};

class CurveOnRealMesh : public ::testing::TestWithParam<RealMesh> {};

TEST_P(CurveOnRealMesh, CertificateHoldsAndCurveLiesOnTheSurface) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const RealMesh& m = GetParam();
  const auto dir = output_dir();
  const auto in = shared_meshes() / m.file;
  const auto curve = dir / "curve.obj", tri = dir / "cycle.obj";
  const CommandResult r = run_cli({"curve", in.string(), "-o", curve.string(), "--triangles", tri.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("repaired") != std::string::npos, m.needs_repair) << r.err;
  if (std::string(m.file) == "moebius.obj") {
    EXPECT_NE(r.err.find("note: component 0 is not orientable"), std::string::npos) << r.err;
  }

  const ObjGroups certificate = parse_obj_groups(tri);
  const CertificateFacts facts = check_certificate(certificate);
  EXPECT_EQ(facts.problem, "");
  if (m.components > 0) {
    EXPECT_EQ(facts.cycles, m.components);
  }
  if (m.triangles > 0) {
    EXPECT_EQ(facts.triangles, m.triangles);
  }

  const ObjGroups lines = parse_obj_groups(curve);
  ASSERT_EQ(int(lines.lines.size()), facts.cycles);
  for (const auto& l : lines.lines) {
    ASSERT_GE(l.size(), 3u);
    EXPECT_EQ(l.front(), l.back()) << "each curve is a closed l element";
  }
  EXPECT_LT(curve_distance_ratio(lines, certificate), 0.25);

  // A PLY curve is laid out (header and edges) from the cycles' sizes before the cycles
  // exist: it must hold the same curves, point for point.
  const auto ply = dir / "curve.ply";
  const CommandResult p = run_cli({"curve", in.string(), "-o", ply.string()});
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const Polylines from_ply = read_polylines(ply), from_obj = read_polylines(curve);
  EXPECT_EQ(from_ply.start, from_obj.start);
  EXPECT_TRUE(from_ply.points == from_obj.points);
}

INSTANTIATE_TEST_SUITE_P(Index, CurveOnRealMesh, ::testing::ValuesIn(real_meshes), [](const auto& param_info) {
  return test_name(param_info.param.file);
});

// --max-faces refuses a larger input before any work, with exit code 1 and no output,
// in each command that makes something from a mesh.
TEST(CliCurve, MaxFacesRefusesLargerInputsInEveryCommand) {
  const auto dir = output_dir();
  const auto mesh = dir / "sphere.obj";
  ASSERT_EQ(run_cli({"generate", "sphere", "--faces", "500", "-o", mesh.string()}).exit_code, 0);
  for (const auto& [command, output] : {std::pair{"curve", "curve.obj"}, {"wire", "wire.stl"}, {"duotone", "duotone.obj"}}) {
    const auto out = dir / output;
    const CommandResult refused = run_cli({command, mesh.string(), "-o", out.string(), "--max-faces", "100"});
    EXPECT_EQ(refused.exit_code, 1) << command;
    EXPECT_NE(refused.err.find(mesh.string() + ": "), std::string::npos) << command << ": " << refused.err;
    EXPECT_NE(refused.err.find(" faces, more than the limit of 100"), std::string::npos) << command << ": " << refused.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << command;
    EXPECT_EQ(run_cli({command, mesh.string(), "-o", out.string(), "--max-faces", "100000"}).exit_code, 0) << command;
  }
}

// --strict refuses what the default repairs, naming the file and the problem.
TEST(CliCurve, StrictRefusesBrokenMeshesPrecisely) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  for (const char* file : {"hourglass_ico.obj", "triple_vierbein.obj", "conrod.stl", "beveledcube.obj"}) {
    const auto out = dir / (std::string(file) + ".obj");
    const CommandResult r = run_cli({"curve", (shared_meshes() / file).string(), "-o", out.string(), "--strict"});
    EXPECT_EQ(r.exit_code, 1) << file;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << file;
  }
}

TEST(CliCurve, SameSeedSameBytesOtherSeedOtherCurve) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  const auto in = (shared_meshes() / "torus.obj").string();
  for (const char* ext : {".obj", ".ply", ".json", ".svg"}) {
    const auto a = dir / (std::string("a") + ext), b = dir / (std::string("b") + ext), c = dir / (std::string("c") + ext);
    ASSERT_EQ(run_cli({"curve", in, "-o", a.string(), "--seed", "17"}).exit_code, 0);
    ASSERT_EQ(run_cli({"curve", in, "-o", b.string(), "--seed", "17"}).exit_code, 0);
    ASSERT_EQ(run_cli({"curve", in, "-o", c.string(), "--seed", "18"}).exit_code, 0);
    EXPECT_EQ(read_file(a), read_file(b)) << ext;
    EXPECT_NE(read_file(a), read_file(c)) << ext;
  }
}

// --branches: more leaves (which -v prints) the higher it is, a certificate of one cycle
// at each value, and a refusal with another tree than random.
TEST(CliCurve, BranchesSetTheLeavesThatVerbosePrints) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  const auto in = (shared_meshes() / "eight.off").string(), tri = (dir / "cycle.obj").string(),
             out = (dir / "curve.ply").string();
  const auto leaves = [&](const char* branches) {
    const CommandResult r = run_cli({"curve", in, "-o", out, "--spacing", "0.05", "--branches", branches, "--triangles", tri, "-v"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(check_certificate(parse_obj_groups(tri)).cycles, 1);
    const size_t at = r.err.find("tree: ");
    EXPECT_NE(at, std::string::npos) << r.err;
    return at == std::string::npos ? -1 : std::stol(r.err.substr(at + 6));
  };
  const long snakes = leaves("0"), half = leaves("0.5"), bushes = leaves("1");
  EXPECT_LT(snakes, half);
  EXPECT_LT(half, bushes);
  const CommandResult refused = run_cli({"curve", in, "-o", out, "--branches", "0.5", "--tree", "dfs"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--branches grows a tree of its own"), std::string::npos) << refused.err;
}

TEST(CliCurve, EveryTreeQuadAndSmoothingGivesOneCycle) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  const auto tri = dir / "cycle.obj", out = dir / "curve.ply";
  for (const char* tree : {"random", "uniform", "bfs", "dfs"})
    for (const char* quad : {"dual-simplest", "catmull-clark"})
      for (const char* smooth : {"bspline", "catmull-rom", "none"}) {
        SCOPED_TRACE(std::string(tree) + " " + quad + " " + smooth);
        const CommandResult r = run_cli({"curve", (shared_meshes() / "eight.off").string(), "-o", out.string(), "--tree",
                                         tree, "--quad", quad, "--smooth", smooth, "--samples", "2", "--triangles",
                                         tri.string()});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const CertificateFacts facts = check_certificate(parse_obj_groups(tri));
        EXPECT_EQ(facts.problem, "");
        EXPECT_EQ(facts.cycles, 1);
        EXPECT_EQ(facts.euler_characteristic, -2); // genus 2, like the input
      }
  // An all-quad mesh used as it is.
  const CommandResult r = run_cli({"curve", (shared_meshes() / "fandisk_quads.off").string(), "-o", out.string(),
                                   "--quad", "none", "--triangles", tri.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CertificateFacts facts = check_certificate(parse_obj_groups(tri));
  EXPECT_EQ(facts.problem, "");
  EXPECT_EQ(facts.triangles, 2 * 764);
}

// Taubin's cycle needs a closed quad mesh: with boundary, catmull-clark and none refuse
// with the reason and the way out, and leave no file.
TEST(CliCurve, QuadModesRefuseBoundaries) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto out = output_dir() / "curve.obj";
  const CommandResult r =
      run_cli({"curve", (shared_meshes() / "moebius.obj").string(), "-o", out.string(), "--quad", "none"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("need a closed mesh"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // The refusal names the file, as the readers' refusals do.
  const auto sphere = shared_meshes() / "sphere.obj";
  const CommandResult triangles = run_cli({"curve", sphere.string(), "-o", out.string(), "--quad", "none"});
  EXPECT_EQ(triangles.exit_code, 1);
  EXPECT_EQ(triangles.err.rfind("meander: " + sphere.string() + ": face 0 has 3 vertices: quad none needs", 0), 0u) << triangles.err;
}

TEST(CliCurve, UsageErrorsExitWithTwoAndWriteNothing) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto dir = output_dir();
  const std::string in = (shared_meshes() / "tetrahedron.obj").string();
  const std::vector<std::vector<std::string>> bad = {
      {"curve", in},                                                   // no -o
      {"curve", in, "-o", (dir / "x.obj").string(), "--tree", "prim"},  // unknown tree
      {"curve", in, "-o", (dir / "x.obj").string(), "--samples", "0"},  // out of range
      {"curve", in, "-o", (dir / "x.obj").string(), "--quad", "loop"},  // unknown quadrangulation
      {"curve", in, "-o", (dir / "x.xyz").string()},                    // unknown output format
      {"frobnicate"},                                                  // unknown subcommand
  };
  for (const auto& args : bad) {
    const CommandResult r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args.back() << ": " << r.err;
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(CliCurve, MissingInputAndMissingFolderAreRefused) {
  const auto dir = output_dir();
  CommandResult r = run_cli({"curve", (dir / "nope.obj").string(), "-o", (dir / "x.obj").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("nope.obj"), std::string::npos) << r.err;
  r = run_cli({"generate", "sphere", "-o", (dir / "missing" / "x.obj").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// A malformed file is refused through the CLI with the reader's file:line message and
// exit code 1, and neither the curve nor the certificate appears.
TEST(CliCurve, MalformedInputLeavesNoOutput) {
  const auto dir = output_dir();
  const auto bad = write_file("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  const auto curve = dir / "curve.obj", tri = dir / "cycle.obj";
  const CommandResult r = run_cli({"curve", bad.string(), "-o", curve.string(), "--triangles", tri.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.obj:4: "), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(curve));
  EXPECT_FALSE(std::filesystem::exists(tri));
  const CommandResult info = run_cli({"info", bad.string()});
  EXPECT_EQ(info.exit_code, 1);
  EXPECT_NE(info.err.find("bad.obj:4: "), std::string::npos) << info.err;
}

TEST(CliCurve, HelpOnEverySubcommand) {
  for (const char* sub : {"curve", "info", "generate"}) {
    const CommandResult r = run_cli({sub, "--help"});
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
}

// Generated shapes of every kind the issue names: genus 0..3, boundary, Möbius.
TEST(CliCurve, GeneratedShapes) {
  const auto dir = output_dir();
  struct Shape {
    std::vector<std::string> args;
    long chi;
  };
  const Shape shapes[] = {{{"sphere"}, 2}, {{"torus"}, 0}, {{"pretzel"}, -2}, {{"genus", "--genus", "3"}, -4},
                          {{"grid"}, 1},   {{"moebius"}, 0}};
  for (const Shape& s : shapes) {
    const auto mesh = dir / (s.args[0] + ".ply"), tri = dir / (s.args[0] + "_cycle.obj"), curve = dir / (s.args[0] + ".obj");
    std::vector<std::string> gen = {"generate"};
    gen.insert(gen.end(), s.args.begin(), s.args.end());
    gen.insert(gen.end(), {"-o", mesh.string(), "--faces", "3000"});
    ASSERT_EQ(run_cli(gen).exit_code, 0) << s.args[0];
    const CommandResult r = run_cli({"curve", mesh.string(), "-o", curve.string(), "--triangles", tri.string(), "--tree", "uniform"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const ObjGroups certificate = parse_obj_groups(tri);
    const CertificateFacts facts = check_certificate(certificate);
    EXPECT_EQ(facts.problem, "") << s.args[0];
    EXPECT_EQ(facts.cycles, 1) << s.args[0];
    EXPECT_EQ(facts.euler_characteristic, s.chi) << s.args[0];
    EXPECT_LT(curve_distance_ratio(parse_obj_groups(curve), certificate), 0.25) << s.args[0];
  }
}

TEST(CliInfo, ReportsTopologyAsJson) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const CommandResult r = run_cli({"info", (shared_meshes() / "stanford-bunny_original_holes.obj").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* fact : {"\"vertices\": 35947", "\"faces\": 69451", "\"boundary_loops\": 5", "\"unreferenced_vertices\": 1113", "\"edges\": 104288"})
    EXPECT_NE(r.out.find(fact), std::string::npos) << fact << "\n" << r.out;
  const CommandResult text = run_cli({"info", (shared_meshes() / "moebius.obj").string()});
  ASSERT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find("non-orientable"), std::string::npos) << text.out;
}

} // namespace
} // namespace meander::test
