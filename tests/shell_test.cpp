// Two-colour prints of a duotone (issue 38): the surface thickened into a shell and cut
// along the curve into two solids, judged by CGAL (each closed, outward, free of
// self-intersection; their union one shell whose volume is theirs together, so they do
// not overlap, and whose outside is the painted surface), the 3MF read back by lib3mf and
// opened by PrusaSlicer.
#include "cgal_judge.h"
#include "test_support.h"

#include "meander/check.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/printability.h"
#include "meander/shapes.h"
#include "meander/shell.h"
#include "meander/solid_union.h"

#include <Model/COM/NMR_DLLInterfaces.h>
#include <gmock/gmock.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

namespace meander {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

Duotone duotone_of(const PolygonMesh& mesh, const DuotoneJob& job) {
  const RepairResult r = repair(mesh, "test");
  return make_duotone(r.mesh, r.connectivity, job);
}

// Straight tiles (a few triangles a quad, where arcs take some 36) unless said otherwise:
// the same shell, judged in a fraction of the time.
DuotoneJob job_of(double model_size, double wall, Quadrangulation quad = Quadrangulation::dual_simplest,
                  TileStyle tiles = TileStyle::triangles) {
  DuotoneJob job;
  job.model_size = model_size;
  job.duotone.quadrangulation = quad;
  job.tiles.style = tiles;
  job.shell = wall;
  return job;
}

// The volume the duotone's surface (its quads, split at the 0-2 fold as the tiles are)
// encloses: the outside of the shell.
double surface_volume(const Duotone& d) {
  double volume = 0;
  for (int32_t q = 0; q < d.quads.num_quads(); ++q) {
    const auto& c = d.quads.quads[size_t(q)];
    const auto p = [&](int k) { return to_double(d.quads.positions[size_t(c[size_t(k)])]); };
    if (c[1] >= 0) volume += dot(p(0), cross(p(1), p(2))) / 6;
    volume += dot(p(0), cross(p(2), p(3))) / 6;
  }
  return std::abs(volume);
}

// Each solid of a shell: closed, outward, clear of itself, of the volume reported.
void expect_solids(const SplitShell& shell) {
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE("solid " + std::to_string(k));
    const test::CgalVerdict v = test::cgal_judge(shell.solids[size_t(k)]);
    ASSERT_TRUE(v.loaded);
    EXPECT_TRUE(v.closed);
    EXPECT_FALSE(v.self_intersecting);
    EXPECT_TRUE(v.outward);
    EXPECT_NEAR(v.volume, shell.volumes[size_t(k)], 1e-6 * v.volume);
    EXPECT_GT(v.volume, 0);
  }
}

// The checks every shell must pass; `closed`: the surface has no boundary, so the union's
// outside encloses what the surface does (to `within` of it: a sampled shell's outside
// lies near the surface, not on it).
void expect_two_solids(const Duotone& d, const SplitShell& shell, bool closed, double within = 1e-4) {
  expect_solids(shell);
  // They overlap nowhere: the union's volume is the sum (an overlap of 0.1% would show).
  const PolygonMesh both = unite_solids(shell.solids[0], shell.solids[1]).mesh;
  const test::CgalVerdict u = test::cgal_judge(both);
  ASSERT_TRUE(u.loaded);
  EXPECT_TRUE(u.closed);
  EXPECT_FALSE(u.self_intersecting);
  EXPECT_NEAR(u.volume, shell.volumes[0] + shell.volumes[1], 1e-3 * u.volume);
  if (!closed) return;
  // Its outside is the painted surface: the largest component encloses what it does.
  const PrintabilityReport report = check_printability(both, {.self_intersections = false, .thickness = false});
  double outside = 0;
  for (const SolidComponent& c : report.components) outside = std::max(outside, c.volume);
  EXPECT_NEAR(outside, surface_volume(d), within * outside);
  EXPECT_LT(u.volume, outside);
}

struct Case {
  const char* name;
  PolygonMesh (*make)();
  bool closed;
  double clearance; // a clearance these quads take (at most a fifth of their size)
};

const Case kShapes[] = {{"sphere", [] { return sphere(400); }, true, 0.4},
                        {"torus", [] { return torus(600); }, true, 0.4},
                        {"genus_2", [] { return genus_surface(2, 1200); }, true, 0.15},
                        {"genus_3", [] { return genus_surface(3, 1600); }, true, 0.08},
                        {"grid_a_disc", [] { return grid(300); }, false, 0.4}};

class ShellOn : public ::testing::TestWithParam<Case> {};

TEST_P(ShellOn, TwoSolidsThatMakeTheShell) {
  const DuotoneJob job = job_of(100, 2);
  const Duotone d = duotone_of(GetParam().make(), job);
  const SplitShell shell = make_shell(d, job);
  expect_two_solids(d, shell, GetParam().closed);
  EXPECT_GT(shell.thinnest, 0);
  EXPECT_LE(shell.thinnest, 2 + 1e-9);
}

// With a clearance the two solids are each still closed, outward and clear of
// themselves, but never nearer each other than 0.45 of it; the volume they lose is a
// slab about the clearance wide along the cut, through the wall.
TEST_P(ShellOn, AClearanceDrawsTheTwoSolidsApart) {
  DuotoneJob job = job_of(100, 2);
  const Duotone d = duotone_of(GetParam().make(), job);
  const SplitShell joined = make_shell(d, job);
  job.clearance = GetParam().clearance;
  const SplitShell apart = make_shell(d, job);
  expect_solids(apart);
  for (int k = 0; k < 2; ++k)
    EXPECT_GE(test::cgal_least_distance(apart.solids[size_t(k)], apart.solids[size_t(1 - k)]), 0.45 * job.clearance);
  EXPECT_GE(apart.apart, 0.45 * job.clearance);
  const double lost = joined.volumes[0] + joined.volumes[1] - apart.volumes[0] - apart.volumes[1];
  const double slab = job.clearance * 2 * total_length(separating_curves(d, job.tiles.style));
  EXPECT_GT(lost, 0.5 * slab);
  EXPECT_LT(lost, 1.5 * slab);
  EXPECT_THAT(shell_summary(apart, job), HasSubstr("apart"));
}

INSTANTIATE_TEST_SUITE_P(GenusZeroToThreeAndADisc, ShellOn, ::testing::ValuesIn(kShapes),
                         [](const ::testing::TestParamInfo<Case>& shape) { return std::string(shape.param.name); });

TEST(Shell, ASphereHasTheWallAskedEverywhere) {
  // A round sphere 100 mm across with a 2 mm wall: the shell between two spheres, less
  // the faceting (the inside's facets are the outside's, 2 mm in).
  const DuotoneJob job = job_of(100, 2, Quadrangulation::catmull_clark, TileStyle::truchet);
  const Duotone d = duotone_of(sphere(2000), job);
  const SplitShell shell = make_shell(d, job);
  EXPECT_EQ(shell.reduced_corners, 0);
  EXPECT_NEAR(shell.thinnest, 2, 1e-3);
  const double outside = surface_volume(d), radius = std::cbrt(outside * 3 / (4 * std::numbers::pi));
  const double expected = outside * (1 - std::pow((radius - 2) / radius, 3));
  EXPECT_NEAR(shell.volumes[0] + shell.volumes[1], expected, 0.01 * expected);
}

TEST(Shell, ThinPartsGetAThinnerWallAndTheReportSaysWhere) {
  // A torus 10 mm across whose tube is about 2.3 mm thick: 1.5 mm walls would meet in
  // the middle, and the 1.2 mm a printer makes do not fit either.
  DuotoneJob job = job_of(10, 1.5);
  job.min_thickness = 1.2;
  const Duotone d = duotone_of(torus(800), job);
  const SplitShell shell = make_shell(d, job);
  expect_two_solids(d, shell, true);
  EXPECT_GT(shell.reduced_corners, 0);
  EXPECT_GT(shell.below_floor_corners, 0);
  EXPECT_LT(shell.thinnest, 1.2);
  const std::string summary = shell_summary(shell, job);
  EXPECT_THAT(summary, HasSubstr("thinner at"));
  EXPECT_THAT(summary, HasSubstr("not printable there"));
}

TEST(Shell, SameSolidsEveryRun) {
  const DuotoneJob job = job_of(100, 2);
  const Duotone d = duotone_of(genus_surface(2, 800), job);
  const SplitShell a = make_shell(d, job), b = make_shell(d, job);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(a.solids[size_t(k)].positions, b.solids[size_t(k)].positions);
    EXPECT_EQ(a.solids[size_t(k)].face_vertices, b.solids[size_t(k)].face_vertices);
  }
}

TEST(Shell, RefusesANonOrientableSurfaceAndBadWalls) {
  DuotoneJob job = job_of(100, 2);
  const Duotone moebius_band = duotone_of(moebius(400), job);
  try {
    make_shell(moebius_band, job);
    FAIL() << "a Möbius band was thickened";
  } catch (const TopologyError& e) {
    EXPECT_THAT(e.what(), HasSubstr("not orientable"));
  }
  const Duotone d = duotone_of(sphere(200), job);
  job.shell = 0.5; // below the 0.8 mm floor of a model in millimetres
  EXPECT_THROW(make_shell(d, job), ParameterError);
  job.shell = -1;
  EXPECT_THROW(make_shell(d, job), ParameterError);
  job.shell.reset();
  EXPECT_THROW(make_shell(d, job), UsageError);
}

TEST(Shell, SpotAtASpacing) {
  MEANDER_REQUIRE_SHARED_MESHES();
  DuotoneJob job = job_of(100, 1.5, Quadrangulation::catmull_clark);
  job.spacing = 4;
  const PolygonMesh mesh = read_mesh(test::shared_meshes() / "spot_triangulated.obj");
  const RepairResult r = repair(mesh, "spot");
  const Duotone d = make_duotone(r.mesh, r.connectivity, job);
  const SplitShell shell = make_shell(d, job);
  expect_two_solids(d, shell, true);
}

// A scan whose ears and tail are thinner than two walls and fold sharply at this size: no
// wall follows the quads there, so the shell is sampled (CGAL's Mesh_3), solid in the thin
// parts, and is still two closed, outward solids clear of themselves that make the shell
// together, each one piece (CGAL, PrusaSlicer), though the colour regions' necks are
// narrower than its cells in places.
TEST(Shell, AScanTooThinForAWallThatFollowsTheQuadsIsSampled) {
  MEANDER_REQUIRE_SHARED_MESHES();
  DuotoneJob job = job_of(40, 1.5, Quadrangulation::catmull_clark, TileStyle::truchet);
  job.spacing = 3;
  const PolygonMesh mesh = read_mesh(test::shared_meshes() / "kitten.off");
  const RepairResult r = repair(mesh, "kitten");
  const Duotone d = make_duotone(r.mesh, r.connectivity, job);
  const SplitShell shell = make_shell(d, job);
  ASSERT_TRUE(shell.sampled) << "the wall followed the quads: this test needs a surface it cannot follow";
  // Its outside lies within a tenth of a wall (0.15 mm) of the surface: over the kitten's
  // 2,700 mm² at 40 mm, up to 400 mm³ of its 6,400 (6%) were it all to one side; it is
  // off by 1.1%, and 3% would show a shift to one side.
  expect_two_solids(d, shell, true, 0.03);
  EXPECT_THAT(shell_summary(shell, job), HasSubstr("solid where the model is thinner than two walls"));
  MEANDER_REQUIRE(test::prusa_slicer_found(), "prusa-slicer is not installed (Debian's prusa-slicer; make test installs it)");
  for (int k = 0; k < 2; ++k) {
    const fs::path part = test::output_dir() / ("sampled_" + std::to_string(k) + ".stl");
    write_mesh(shell.solids[size_t(k)], part);
    const test::SlicerInfo info = test::prusa_slicer_info(part);
    ASSERT_EQ(info.status, 0) << info.text;
    EXPECT_TRUE(info.manifold) << info.text;
    EXPECT_EQ(info.parts, 1) << info.text;
  }
}

// ---- The CLI, the 3MF and PrusaSlicer ----------------------------------------------------

struct Read3mfParts {
  int mesh_objects = 0;
  DWORD triangles = 0;
  std::vector<std::array<uint8_t, 3>> colors; // of the base materials
  std::vector<DWORD> material;                // per triangle: its base material's index
  std::vector<std::string> attachments;
};

Read3mfParts read_parts(const fs::path& path) {
  Read3mfParts out;
  NMR::PLib3MFModel* model = nullptr;
  NMR::PLib3MFModelReader* reader = nullptr;
  EXPECT_EQ(NMR::lib3mf_createmodel(&model), LIB3MF_OK);
  EXPECT_EQ(NMR::lib3mf_model_queryreader(model, "3mf", &reader), LIB3MF_OK);
  // lib3mf drops the parts it does not know unless told which to keep.
  EXPECT_EQ(NMR::lib3mf_reader_addrelationtoreadutf8(reader, "http://schemas.slic3r.org/3mf/2017/06/model-config"), LIB3MF_OK);
  EXPECT_EQ(NMR::lib3mf_reader_readfromfileutf8(reader, path.c_str()), LIB3MF_OK);
  NMR::PLib3MFModelResourceIterator* it = nullptr;
  EXPECT_EQ(NMR::lib3mf_model_getbasematerials(model, &it), LIB3MF_OK);
  BOOL more = false;
  while (NMR::lib3mf_resourceiterator_movenext(it, &more) == LIB3MF_OK && more) {
    NMR::PLib3MFModelResource* group = nullptr;
    NMR::lib3mf_resourceiterator_getcurrent(it, &group);
    DWORD count = 0;
    NMR::lib3mf_basematerial_getcount(group, &count);
    for (DWORD i = 0; i < count; ++i) {
      BYTE r = 0, g = 0, b = 0, a = 0;
      NMR::lib3mf_basematerial_getdisplaycolor(group, i, &r, &g, &b, &a);
      out.colors.push_back({r, g, b});
    }
    NMR::lib3mf_release(group);
  }
  NMR::lib3mf_release(it);
  EXPECT_EQ(NMR::lib3mf_model_getmeshobjects(model, &it), LIB3MF_OK);
  while (NMR::lib3mf_resourceiterator_movenext(it, &more) == LIB3MF_OK && more) {
    NMR::PLib3MFModelResource* object = nullptr;
    NMR::lib3mf_resourceiterator_getcurrent(it, &object);
    if (out.mesh_objects++ == 0) {
      NMR::lib3mf_meshobject_gettrianglecount(object, &out.triangles);
      NMR::PLib3MFPropertyHandler* properties = nullptr;
      EXPECT_EQ(NMR::lib3mf_meshobject_createpropertyhandler(object, &properties), LIB3MF_OK);
      std::vector<DWORD> groups(out.triangles);
      out.material.resize(out.triangles);
      EXPECT_EQ(NMR::lib3mf_propertyhandler_getbasematerialarray(properties, groups.data(), out.material.data()), LIB3MF_OK);
      NMR::lib3mf_release(properties);
    }
    NMR::lib3mf_release(object);
  }
  NMR::lib3mf_release(it);
  DWORD attachments = 0;
  NMR::lib3mf_model_getattachmentcount(model, &attachments);
  for (DWORD i = 0; i < attachments; ++i) {
    char name[256] = {};
    ULONG needed = 0;
    NMR::lib3mf_model_getattachmentpathutf8(model, i, name, sizeof name, &needed);
    out.attachments.push_back(name);
  }
  NMR::lib3mf_release(reader);
  NMR::lib3mf_release(model);
  return out;
}

TEST(CliShell, TwoColourPrintIn3mfAndPartsThatPrusaSlicerOpens) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const fs::path dir = test::output_dir();
  const std::vector<std::string> args = {"duotone", (test::shared_meshes() / "spot_triangulated.obj").string(),
                                         "--model-size", "100mm", "--spacing", "4mm", "--shell", "1.5mm",
                                         "--colors", "#ff0000,#00ff00", "-o", (dir / "print.3mf").string(),
                                         "--parts", (dir / "a.stl").string() + "," + (dir / "b.stl").string()};
  const test::CommandResult r = test::run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("2 solids, one per colour, closed and outward"));
  const std::string first = test::read_file(dir / "print.3mf");
  ASSERT_EQ(test::run_cli(args).exit_code, 0);
  EXPECT_EQ(test::read_file(dir / "print.3mf"), first); // the same bytes again

  const PolygonMesh a = read_mesh(dir / "a.stl"), b = read_mesh(dir / "b.stl");
  for (const PolygonMesh* part : {&a, &b}) {
    const test::CgalVerdict v = test::cgal_judge(*part);
    EXPECT_TRUE(v.closed && v.outward && !v.self_intersecting);
  }
  const Read3mfParts back = read_parts(dir / "print.3mf");
  EXPECT_EQ(back.mesh_objects, 1);
  ASSERT_EQ(back.triangles, DWORD(a.num_faces() + b.num_faces()));
  ASSERT_EQ(back.colors.size(), 2u);
  EXPECT_EQ(back.colors[0], (std::array<uint8_t, 3>{255, 0, 0}));
  EXPECT_EQ(back.colors[1], (std::array<uint8_t, 3>{0, 255, 0}));
  // Part after part, each triangle with its part's material.
  EXPECT_EQ(std::count(back.material.begin(), back.material.end(), 0u), a.num_faces());
  EXPECT_TRUE(std::is_partitioned(back.material.begin(), back.material.end(), [](DWORD m) { return m == 0; }));
  EXPECT_THAT(back.attachments, ::testing::Contains("/Metadata/Slic3r_PE_model.config"));

  MEANDER_REQUIRE(test::prusa_slicer_found(), "prusa-slicer is not installed (Debian's prusa-slicer; make test installs it)");
  const test::SlicerInfo info = test::prusa_slicer_info(dir / "print.3mf");
  ASSERT_EQ(info.status, 0) << info.text;
  EXPECT_TRUE(info.manifold) << info.text;
  EXPECT_EQ(info.parts, 2) << info.text;
  EXPECT_EQ(info.objects, 1) << info.text; // one object: the two parts stay together
}

// A scan too thin at this size for a wall that follows the quads: the CLI samples the
// shell, says so, makes the same bytes every run, and PrusaSlicer opens the 3MF as one
// object of two manifold parts.
TEST(CliShell, AThinScanIsSampledIntoTheSameTwoColourPrintEveryRun) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const fs::path dir = test::output_dir();
  const std::vector<std::string> args = {"duotone", (test::shared_meshes() / "kitten.off").string(), "--model-size", "40mm",
                                         "--spacing", "3mm", "--shell", "1.5mm", "-o", (dir / "print.3mf").string(),
                                         "--parts", (dir / "a.stl").string() + "," + (dir / "b.stl").string()};
  const test::CommandResult r = test::run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("the shell was sampled"));
  const std::string first = test::read_file(dir / "print.3mf");
  ASSERT_EQ(test::run_cli(args).exit_code, 0);
  EXPECT_EQ(test::read_file(dir / "print.3mf"), first);
  for (const char* name : {"a.stl", "b.stl"}) {
    const test::CgalVerdict v = test::cgal_judge(read_mesh(dir / name));
    EXPECT_TRUE(v.closed && v.outward && !v.self_intersecting) << name;
  }
  MEANDER_REQUIRE(test::prusa_slicer_found(), "prusa-slicer is not installed (Debian's prusa-slicer; make test installs it)");
  const test::SlicerInfo info = test::prusa_slicer_info(dir / "print.3mf");
  ASSERT_EQ(info.status, 0) << info.text;
  EXPECT_TRUE(info.manifold) << info.text;
  EXPECT_EQ(info.parts, 2) << info.text;
  EXPECT_EQ(info.objects, 1) << info.text;
}

// Two pieces to print apart, written to a.stl and b.stl in `dir` by a command that printed
// `summary`: each closed, outward and clear of itself, never nearer the other than 0.45
// of the clearance (CGAL measures), each opened by PrusaSlicer as manifold and in as many
// parts as the summary says (one unless it says "in A and B separate parts").
void expect_pieces_apart(const fs::path& dir, double clearance, const std::string& summary) {
  const std::array<PolygonMesh, 2> parts{read_mesh(dir / "a.stl"), read_mesh(dir / "b.stl")};
  for (int k = 0; k < 2; ++k) {
    const test::CgalVerdict v = test::cgal_judge(parts[size_t(k)]);
    EXPECT_TRUE(v.closed && v.outward && !v.self_intersecting);
    EXPECT_GE(test::cgal_least_distance(parts[size_t(k)], parts[size_t(1 - k)]), 0.45 * clearance);
  }
  std::array<int, 2> said{1, 1};
  if (std::smatch m; std::regex_search(summary, m, std::regex("in (\\d+) and (\\d+) separate parts")))
    said = {std::stoi(m[1]), std::stoi(m[2])};
  MEANDER_REQUIRE(test::prusa_slicer_found(), "prusa-slicer is not installed (Debian's prusa-slicer; make test installs it)");
  for (int k = 0; k < 2; ++k) {
    const test::SlicerInfo info = test::prusa_slicer_info(dir / (k == 0 ? "a.stl" : "b.stl"));
    ASSERT_EQ(info.status, 0) << info.text;
    EXPECT_TRUE(info.manifold) << info.text;
    EXPECT_EQ(info.parts, said[size_t(k)]) << summary << "\n" << info.text;
  }
}

// Runs `meander duotone MESH ARGS -o print.3mf --parts a.stl,b.stl` in `dir`.
test::CommandResult print_apart(const fs::path& dir, const char* mesh, std::vector<std::string> args) {
  args.insert(args.begin(), {"duotone", (test::shared_meshes() / mesh).string()});
  args.insert(args.end(), {"-o", (dir / "print.3mf").string(), "--parts", (dir / "a.stl").string() + "," + (dir / "b.stl").string()});
  return test::run_cli(args);
}

TEST(CliShell, AClearanceMakesTwoPiecesToPrintApart) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const fs::path dir = test::output_dir();
  const test::CommandResult r =
      print_apart(dir, "spot_triangulated.obj", {"--model-size", "100mm", "--spacing", "5mm", "--shell", "1.5mm", "--clearance", "0.3mm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("apart"));
  EXPECT_THAT(r.err, Not(HasSubstr("separate parts")));
  expect_pieces_apart(dir, 0.3, r.err);
}

// The same where no wall follows the quads (the kitten's ears at 40 mm): the shell is
// sampled with the gap left out (which at this small size cuts a narrow neck of a colour
// region through, so a piece may fall into parts).
TEST(CliShell, AThinScanIsSampledIntoTwoPiecesToPrintApart) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const fs::path dir = test::output_dir();
  const test::CommandResult r =
      print_apart(dir, "kitten.off", {"--model-size", "40mm", "--spacing", "4mm", "--shell", "1.5mm", "--clearance", "0.5mm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("the shell was sampled"));
  EXPECT_THAT(r.err, HasSubstr("apart"));
  expect_pieces_apart(dir, 0.5, r.err);
}

// Where the wall follows the quads but the gap would leave too little of the narrowest
// (the bevelled cube's bevels, at its own density): sampled instead of refused. The
// bevels' quads go into the gap, so each piece falls into its six faces' parts, as the
// summary says.
TEST(CliShell, QuadsTooSmallForTheGapAreSampled) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const fs::path dir = test::output_dir();
  const test::CommandResult r =
      print_apart(dir, "beveledcube.obj", {"--model-size", "40mm", "--shell", "1mm", "--clearance", "2mm"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("or its quads too small for the gap: the shell was sampled"));
  EXPECT_THAT(r.err, HasSubstr("separate parts"));
  expect_pieces_apart(dir, 2, r.err);
}

TEST(CliShell, RefusesBadRequestsWithoutOutput) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const fs::path dir = test::output_dir();
  const std::string eight = (test::shared_meshes() / "eight.off").string();
  const std::string out = (dir / "out.3mf").string();
  struct Refusal {
    std::vector<std::string> args;
    int code;
    const char* says;
  };
  const Refusal refusals[] = {
      {{"duotone", eight, "-o", out}, 2, "add --shell"},
      {{"duotone", eight, "-o", (dir / "out.obj").string(), "--shell", "0.1"}, 2, "-o OUT.3mf or --parts"},
      {{"duotone", eight, "-o", (dir / "out.obj").string(), "--parts", "a.stl,b.stl"}, 2, "add --shell"},
      {{"duotone", eight, "-o", (dir / "out.obj").string(), "--min-thickness", "0.1"}, 2, "--min-thickness"},
      {{"duotone", eight, "-o", out, "--shell", "0.1", "--parts", "a.stl"}, 2, "A.stl,B.stl"},
      {{"duotone", eight, "-o", out, "--model-size", "100mm", "--shell", "0.5mm"}, 2, "--shell"},
      {{"duotone", eight, "-o", out, "--shell", "2mm"}, 2, "unit"},
      {{"duotone", eight, "-o", out, "--clearance", "0.1"}, 2, "--clearance applies to a shell"},
      // The quads made first (the icosahedron's 60 at once), then measured.
      {{"duotone", (test::shared_meshes() / "icosahedron_binary.stl").string(), "-o", out, "--shell", "0.05", "--clearance", "1"},
       2, "too wide for quads of 0.525731"},
      {{"duotone", (test::shared_meshes() / "moebius.obj").string(), "-o", out, "--quad", "dual-simplest", "--shell", "0.01"},
       1, "not orientable"},
  };
  for (const Refusal& refusal : refusals) {
    const test::CommandResult r = test::run_cli(refusal.args);
    EXPECT_EQ(r.exit_code, refusal.code) << refusal.says << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(refusal.says));
    EXPECT_TRUE(fs::is_empty(dir)) << refusal.says;
  }
}

} // namespace
} // namespace meander
