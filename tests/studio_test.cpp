// The studio's library side (studio.h): parameters checked as the CLI checks them, uploads
// read from memory with the CLI's messages, results made by the same calls, and files.
#include "meander/error.h"
#include "meander/io.h"
#include "meander/textured_io.h"
#include "meander/shapes.h"
#include "meander/studio.h"
#include "meander/wire.h"
#include "test_support.h"
#include "view_decoder.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <zip.h>

#include <cstring>
#include <fstream>
#include <map>

namespace meander {
namespace {

using nlohmann::json;

// The files of a zip archive by name, read back by libzip with its consistency checks;
// empty if it does not open.
std::map<std::string, std::string> unzip(const std::string& archive) {
  std::map<std::string, std::string> files;
  zip_source_t* source = zip_source_buffer_create(archive.data(), archive.size(), 0, nullptr);
  zip_t* zip = source ? zip_open_from_source(source, ZIP_CHECKCONS | ZIP_RDONLY, nullptr) : nullptr;
  if (!zip) {
    if (source) zip_source_free(source);
    return files;
  }
  for (zip_int64_t i = 0; i < zip_get_num_entries(zip, 0); ++i) {
    zip_stat_t stat;
    zip_file_t* file = zip_stat_index(zip, zip_uint64_t(i), 0, &stat) == 0 ? zip_fopen_index(zip, zip_uint64_t(i), 0) : nullptr;
    if (!file) continue;
    std::string bytes(stat.size, '\0');
    if (zip_fread(file, bytes.data(), bytes.size()) == zip_int64_t(bytes.size())) files[stat.name] = bytes;
    zip_fclose(file);
  }
  zip_close(zip);
  return files;
}

std::string message_of(std::string_view body) {
  try {
    parse_make_request(body);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(Studio, MakeRequestTakesEveryCliParameter) {
  const MakeRequest r = parse_make_request(R"({"session": "ab", "mode": "variable-ribbon", "quad": "catmull-clark",
      "tree": "dfs", "seed": 42, "smooth": "catmull-rom", "samples": 6, "radius": 0.5, "sides": 5, "s": 0.3,
      "t": 0.9, "thickness": 0.02, "levels": 0})");
  EXPECT_EQ(r.session, "ab");
  EXPECT_EQ(r.params.mode, StudioMode::variable_ribbon);
  EXPECT_EQ(r.params.wire.curve.quadrangulation, Quadrangulation::catmull_clark);
  EXPECT_EQ(r.params.wire.curve.cycle.tree, TreeStrategy::dfs);
  EXPECT_EQ(r.params.wire.curve.cycle.seed, 42u);
  EXPECT_EQ(r.params.wire.curve.curve.smoothing, Smoothing::catmull_rom);
  EXPECT_EQ(r.params.wire.curve.curve.samples, 6);
  EXPECT_EQ(r.params.wire.radius, 0.5);
  EXPECT_EQ(r.params.wire.sides, 5);
  EXPECT_EQ(r.params.wire.s, 0.3);
  EXPECT_EQ(r.params.wire.t, 0.9);
  EXPECT_EQ(r.params.wire.thickness, 0.02);
  EXPECT_EQ(r.params.wire.levels, 0);
  EXPECT_FALSE(parse_make_request(R"({"session": "x", "mode": "constant-wire", "radius": "auto"})").params.wire.radius);
  const MakeRequest d = parse_make_request(R"({"session": "x", "mode": "duotone", "rule": "flip", "colors": "red,#00ff00",
      "tiles": "dots", "texture_size": 256, "subdivide": 2})");
  EXPECT_EQ(d.params.mode, StudioMode::duotone);
  EXPECT_EQ(d.params.duotone.duotone.rule, DuotoneRule::flip);
  EXPECT_EQ(d.params.duotone.tiles.style, TileStyle::dots);
  EXPECT_EQ(d.params.duotone.tiles.colors[1], (Color8{0, 255, 0}));
  EXPECT_EQ(d.params.duotone.tiles.texture_size, 256);
  EXPECT_EQ(d.params.duotone.subdivide, 2);
}

TEST(Studio, MakeRequestRefusalsNameTheKey) {
  EXPECT_EQ(message_of(R"({"session": "x", "s": 1.5})"), "s: expected a number in [0, 1], got 1.5");
  EXPECT_EQ(message_of(R"({"session": "x", "levels": 2.5})"), "levels: expected an integer in [0, 6], got 2.5");
  EXPECT_EQ(message_of(R"({"session": "x", "sides": 2})"), "sides: expected an integer in [3, 64], got 2");
  EXPECT_EQ(message_of(R"({"session": "x", "radius": -1})"), "radius: expected a positive number or auto, got -1");
  EXPECT_EQ(message_of(R"({"session": "x", "seed": -3})"), "seed: expected an integer, got -3");
  EXPECT_EQ(message_of(R"({"session": "x", "colour": "red"})"), "\"colour\": unknown parameter");
  EXPECT_NE(message_of(R"({"session": "x", "tree": "oak"})").find("tree: "), std::string::npos);
  EXPECT_NE(message_of(R"({"session": "x", "mode": "duo"})").find("mode: unknown mode 'duo'"), std::string::npos);
  EXPECT_NE(message_of(R"({"session": "x", "colors": "red"})").find("colors 'red': expected two colours"), std::string::npos);
  EXPECT_EQ(message_of(R"({"session": "x", "subdivide": 6})"), "subdivide: expected an integer in [0, 5], got 6");
  EXPECT_EQ(message_of(R"({"s": 0.5})"), "session: missing (upload a mesh first: POST /api/mesh)");
  EXPECT_EQ(message_of("{\"session\": "), "request body is not valid JSON");
  EXPECT_EQ(message_of("[1, 2]"), "request body: expected a JSON object, got [1,2]");
  EXPECT_NE(message_of(std::string(100000, ' ')).find("at most"), std::string::npos);
}

TEST(Studio, UploadsAreReadFromMemoryWithTheCliMessages) {
  const StudioSurface s = load_studio_surface("dir/../quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  EXPECT_EQ(s.name, "quad.obj"); // only the last component, never a path
  EXPECT_EQ(s.input_faces, 1);
  try {
    load_studio_surface("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    FAIL() << "a face referring to a missing vertex was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("bad.obj:3: ", 0), 0u) << e.what();
  }
  EXPECT_THROW(load_studio_surface("notes.txt", "hello"), UsageError);
  EXPECT_THROW(load_studio_surface("empty.stl", ""), InputError);
}

// tinygltf would resolve a buffer's URI as a file beside the upload: on a server that is
// any file the server can read, so uploads must embed their data.
TEST(Studio, GltfUploadReferringToFilesIsRefused) {
  const std::string gltf = R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "/etc/passwd", "byteLength": 12}]})";
  try {
    load_studio_surface("evil.gltf", gltf);
    FAIL() << "an external buffer URI was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("evil.gltf: buffer 0 refers to the file \"/etc/passwd\""), std::string::npos) << e.what();
  }
  // The same inside a GLB container.
  std::string glb = "glTF";
  auto u32 = [&glb](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
  std::string chunk = gltf;
  while (chunk.size() % 4) chunk += ' ';
  u32(2), u32(uint32_t(20 + chunk.size())), u32(uint32_t(chunk.size()));
  glb += "JSON" + chunk;
  EXPECT_THROW(load_studio_surface("evil.glb", glb), InputError);
}

TEST(Studio, EveryModeMakesWhatTheCliMakes) {
  const StudioSurface surface = demo_surface();
  for (const char* mode : {"curve", "constant-wire", "constant-ribbon", "variable-wire", "variable-ribbon", "duotone"}) {
    SCOPED_TRACE(mode);
    StudioParams params{.mode = parse_studio_mode(mode), .wire = {.levels = 0}};
    const StudioResult r = make_studio_result(surface, params);
    EXPECT_EQ(r.curve.curves.start.size(), 2u); // one closed curve: the pretzel is one component
    EXPECT_GT(r.curve_length, 0);
    if (params.mode == StudioMode::curve) {
      EXPECT_EQ(r.mesh.num_faces(), 0);
      continue;
    }
    if (params.mode == StudioMode::duotone) { // as `meander duotone`: textured quads, one separating curve
      EXPECT_EQ(r.mesh.num_faces(), r.curve.quads.num_quads());
      EXPECT_EQ(r.appearance.texcoords.size(), r.mesh.face_vertices.size());
      continue;
    }
    EXPECT_GT(r.mesh.num_faces(), 0);
    EXPECT_FALSE(r.report.self_intersecting);
    const bool wire = params.mode == StudioMode::constant_wire || params.mode == StudioMode::variable_wire;
    EXPECT_EQ(r.report.watertight, wire);
  }
}

// A wire on a surface that crosses itself (Spot's control mesh: 8 pairs of its own
// triangles) cannot be clear, and the page is told why, as `meander wire` says it; on an
// embedded surface the count is 0.
TEST(Studio, SaysWhenTheSurfaceItselfCrossesItself) {
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto path = test::shared_meshes() / "spot_control_mesh.obj";
  const StudioSurface spot = load_studio_surface(path.filename().string(), test::read_file(path));
  const StudioParams params{.mode = StudioMode::variable_wire, .wire = {.levels = 0}};
  const StudioResult crossing = make_studio_result(spot, params);
  ASSERT_TRUE(crossing.report.self_intersecting);
  EXPECT_GT(crossing.surface_crossings, 0);
  EXPECT_EQ(nlohmann::json::parse(studio_stats_json(crossing))["surface_crossings"], crossing.surface_crossings);
  const StudioResult clear = make_studio_result(demo_surface(), params);
  EXPECT_EQ(nlohmann::json::parse(studio_stats_json(clear))["surface_crossings"], 0);
}

// The variable modes split large polygons, flip caps and collapse needles first, as
// `meander wire --method variable` does, and say how many; the other modes use the mesh
// as it is.
TEST(Studio, VariableModesFlipCapsAndCollapseNeedles) {
  const StudioSurface cap = load_studio_surface("cap.obj", "v 0 0 0\nv 2 0 0\nv 1 0.05 0\nv 1 -1 0\nf 1 2 3\nf 2 1 4\n");
  for (const StudioMode mode : {StudioMode::variable_wire, StudioMode::variable_ribbon, StudioMode::constant_ribbon}) {
    const StudioResult r = make_studio_result(cap, {.mode = mode, .wire = {.levels = 0}, .preview = true});
    const bool variable = mode != StudioMode::constant_ribbon;
    EXPECT_EQ(r.curve.cap_flips, variable ? 1 : 0);
    EXPECT_EQ(nlohmann::json::parse(studio_stats_json(r))["cap_flips"], r.curve.cap_flips);
  }
  // And collapse needles: two, on one short edge of a grid.
  PolygonMesh grid_mesh = grid(18);
  grid_mesh.positions[5] = grid_mesh.positions[6] * 0.99f + grid_mesh.positions[5] * 0.01f;
  const auto needles_path = test::output_dir() / "needles.obj";
  write_mesh(grid_mesh, needles_path);
  const StudioSurface needles = load_studio_surface("needles.obj", test::read_file(needles_path));
  for (const StudioMode mode : {StudioMode::variable_wire, StudioMode::constant_wire}) {
    const StudioResult r = make_studio_result(needles, {.mode = mode, .wire = {.levels = 0}, .preview = true});
    EXPECT_EQ(r.curve.needle_collapses, mode == StudioMode::variable_wire ? 1 : 0);
    EXPECT_EQ(nlohmann::json::parse(studio_stats_json(r))["needle_collapses"], r.curve.needle_collapses);
  }
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto path = test::shared_meshes() / "genus3hexa1.obj";
  const StudioSurface hexagons = load_studio_surface(path.filename().string(), test::read_file(path));
  const StudioResult r = make_studio_result(hexagons, {.mode = StudioMode::variable_ribbon, .wire = {.levels = 0}, .preview = true});
  EXPECT_EQ(r.curve.stars, 82);
  EXPECT_EQ(nlohmann::json::parse(studio_stats_json(r))["stars"], 82);
}

// The session's last result lends its atlas to the next duotone only for the same tile
// options: what is drawn is always the atlas of the options asked for.
TEST(Studio, DuotoneReusesTheAtlasOnlyForTheSameTiles) {
  const StudioSurface surface = demo_surface();
  StudioParams params{.mode = StudioMode::duotone, .duotone = {.tiles = {.texture_size = 64}}};
  const StudioResult first = make_studio_result(surface, params);
  const auto atlas = [](const StudioResult& r) { return r.appearance.materials.at(0).texture.rgba; };
  params.duotone.duotone.seed = 7;
  const StudioResult reseeded = make_studio_result(surface, params, &first);
  EXPECT_EQ(atlas(reseeded), atlas(first));
  EXPECT_EQ(reseeded.mesh.face_vertices, make_studio_result(surface, params).mesh.face_vertices);
  for (const TileOptions& tiles : {TileOptions{.style = TileStyle::dots, .texture_size = 64},
                                   TileOptions{.colors = {Color8{255, 0, 0}, Color8{0, 0, 255}}, .texture_size = 64},
                                   TileOptions{.texture_size = 128}}) {
    params.duotone.tiles = tiles;
    const StudioResult changed = make_studio_result(surface, params, &reseeded);
    EXPECT_EQ(atlas(changed), duotone_atlas(tiles).rgba);
    EXPECT_NE(atlas(changed), atlas(first));
    EXPECT_NE(nlohmann::json::parse(studio_stats_json(changed))["texture"], nlohmann::json::parse(studio_stats_json(first))["texture"]);
  }
  EXPECT_EQ(nlohmann::json::parse(studio_stats_json(first))["texture"], "truchet #f2be22 #1c3e80 64");
}

TEST(Studio, ResultSizeIsKnownBeforeAnyWork) {
  const StudioSurface surface = demo_surface();
  for (const char* mode : {"curve", "constant-wire", "constant-ribbon", "variable-wire", "variable-ribbon", "duotone"}) {
    for (const char* quad : {"dual-simplest", "catmull-clark"}) {
      SCOPED_TRACE(std::string(mode) + " " + quad);
      StudioParams params{.mode = parse_studio_mode(mode), .wire = {.levels = 0}, .duotone = {.tiles = {.texture_size = 256}}};
      params.wire.curve.quadrangulation = params.duotone.duotone.quadrangulation = parse_quadrangulation(quad);
      const StudioResult r = make_studio_result(surface, params);
      const int64_t size = studio_result_size(surface, params);
      if (params.mode == StudioMode::curve) EXPECT_EQ(size, int64_t(r.curve.curves.points.size()));
      else if (params.mode == StudioMode::duotone) EXPECT_GE(size, r.triangles + 256 * 128);
      else EXPECT_EQ(size, r.triangles);
    }
  }
  // Levels, samples and subdivision multiply it as they multiply the work.
  EXPECT_EQ(studio_result_size(surface, {.mode = StudioMode::variable_wire, .wire = {.levels = 3}}),
            16 * studio_result_size(surface, {.mode = StudioMode::variable_wire, .wire = {.levels = 1}}));
  StudioParams many{.mode = StudioMode::curve};
  many.wire.curve.curve.samples = 1000;
  EXPECT_EQ(studio_result_size(surface, many), 250 * studio_result_size(surface, {.mode = StudioMode::curve}));
  // The variable modes split polygons of 5 or more sides into stars first.
  MEANDER_REQUIRE_SHARED_MESHES();
  const auto path = test::shared_meshes() / "genus3hexa1.obj";
  const StudioSurface hexagons = load_studio_surface(path.filename().string(), test::read_file(path));
  for (const StudioMode mode : {StudioMode::variable_wire, StudioMode::variable_ribbon})
    for (const char* quad : {"dual-simplest", "catmull-clark"}) {
      StudioParams params{.mode = mode, .wire = {.levels = 0}};
      params.wire.curve.quadrangulation = params.duotone.duotone.quadrangulation = parse_quadrangulation(quad);
      EXPECT_EQ(studio_result_size(hexagons, params), make_studio_result(hexagons, params).triangles) << quad;
    }
}

// A preview that 2 curve samples would make larger than its budget takes 1, and a wire
// still over it is drawn as its ribbon: on a 4,000-face sphere (12,000 triangles of the
// cycle), a 16-sided wire has 0.77M triangles at 2 samples and 0.38M at 1; a 32-sided one
// 0.77M at 1.
TEST(Studio, APreviewOverItsBudgetTakesFewerSamplesThenARibbon) {
  StudioSurface surface{.name = "sphere.obj"};
  surface.repaired = repair(make_shape("sphere", 4000), surface.name);
  const auto at = [](int sides, int samples, StudioMode mode = StudioMode::constant_wire) {
    StudioParams p{.mode = mode, .wire = {.sides = sides}};
    p.wire.curve.curve.samples = samples;
    return p;
  };
  ASSERT_GT(studio_result_size(surface, at(16, 2)), studio_preview_budget);
  ASSERT_LE(studio_result_size(surface, at(16, 1)), studio_preview_budget);
  StudioParams fewer = at(16, 4);
  fewer.preview = true;
  EXPECT_EQ(studio_result_size(surface, fewer), studio_result_size(surface, at(16, 1)));
  const StudioResult one = make_studio_result(surface, fewer);
  EXPECT_EQ(one.params.wire.curve.curve.samples, 1);
  EXPECT_EQ(one.params.wire.shape, WireShape::wire);
  EXPECT_EQ(one.triangles, studio_result_size(surface, at(16, 1)));
  EXPECT_FALSE(nlohmann::json::parse(studio_stats_json(one)).contains("preview_as_ribbon"));
  StudioParams wide = at(32, 4);
  wide.preview = true;
  ASSERT_GT(studio_result_size(surface, at(32, 1)), studio_preview_budget);
  const StudioResult ribbon = make_studio_result(surface, wide);
  EXPECT_EQ(ribbon.params.wire.shape, WireShape::ribbon);
  EXPECT_EQ(ribbon.triangles, studio_result_size(surface, at(32, 1, StudioMode::constant_ribbon)));
  EXPECT_EQ(nlohmann::json::parse(studio_stats_json(ribbon))["preview_as_ribbon"], true);
  // Within the budget a preview keeps its 2 samples.
  StudioParams narrow{.mode = StudioMode::constant_wire, .preview = true};
  EXPECT_EQ(studio_result_size(surface, narrow), studio_result_size(surface, {.mode = StudioMode::constant_wire}) / 2);
}

// A variable mode's preview whose ribbon is still over the budget has a rung a triangle
// instead of two: on a 45,000-face sphere (135,000 triangles of the cycle) the ribbon has
// 540,000 triangles, 270,000 so.
TEST(Studio, AVariablePreviewOverItsBudgetHasARungATriangle) {
  StudioSurface surface{.name = "sphere.obj"};
  surface.repaired = repair(make_shape("sphere", 45000), surface.name);
  const StudioParams ribbon{.mode = StudioMode::variable_ribbon, .wire = {.levels = 0}};
  ASSERT_GT(studio_result_size(surface, ribbon), studio_preview_budget);
  const int64_t two = make_studio_result(surface, ribbon).triangles; // the slab mesh's needles collapsed: fewer than the bound
  for (const StudioMode mode : {StudioMode::variable_wire, StudioMode::variable_ribbon}) {
    const StudioResult quick = make_studio_result(surface, {.mode = mode, .preview = true});
    EXPECT_EQ(quick.params.wire.shape, WireShape::ribbon);
    EXPECT_EQ(quick.params.wire.rungs, 1);
    EXPECT_EQ(2 * quick.triangles, two);
    EXPECT_EQ(2 * studio_result_size(surface, {.mode = mode, .preview = true}), studio_result_size(surface, ribbon));
    EXPECT_EQ(nlohmann::json::parse(studio_stats_json(quick))["preview_rungs"], 1);
  }
}

TEST(Studio, PreviewIsTheQuickVersionWithoutAReport) {
  const StudioSurface surface = demo_surface();
  StudioParams full{.mode = StudioMode::variable_wire, .wire = {.levels = 2}};
  full.wire.curve.curve.samples = 8;
  StudioParams preview = full;
  preview.preview = true;
  const StudioResult quick = make_studio_result(surface, preview);
  EXPECT_EQ(quick.params.wire.levels, 0);
  EXPECT_EQ(quick.params.wire.curve.curve.samples, 2);
  EXPECT_EQ(quick.params.wire.curve.relax, 2); // of a spacing's 20 rounds of relaxation
  // None where the remeshed surface has more than studio_preview_relax_faces.
  for (const double spacing : {0.5, 0.03}) {
    StudioParams curve{.mode = StudioMode::curve, .preview = true};
    curve.wire.curve.spacing = spacing;
    const int64_t faces = remeshed_faces(surface.repaired.mesh, std::nullopt, spacing, Quadrangulation::dual_simplest);
    ASSERT_EQ(faces > studio_preview_relax_faces, spacing == 0.03) << faces;
    EXPECT_EQ(make_studio_result(surface, curve).params.wire.curve.relax, faces > studio_preview_relax_faces ? 0 : 2);
  }
  const StudioResult level0 = make_studio_result(surface, {.mode = StudioMode::variable_wire, .wire = {.levels = 0}});
  EXPECT_EQ(quick.triangles, level0.triangles);
  EXPECT_EQ(studio_result_size(surface, preview), quick.triangles);
  const auto stats = nlohmann::json::parse(studio_stats_json(quick));
  EXPECT_EQ(stats["preview"], true);
  EXPECT_FALSE(stats.contains("preview_rungs")); // within its budget: two rungs a triangle
  EXPECT_FALSE(stats.contains("watertight"));
  EXPECT_FALSE(stats.contains("self_intersecting"));
  EXPECT_EQ(nlohmann::json::parse(studio_stats_json(level0))["preview"], false);
  // `radius auto` in a preview is the analytic bound, which the full result's check only grows.
  const StudioResult wire = make_studio_result(surface, {.mode = StudioMode::constant_wire, .preview = true});
  const StudioResult checked = make_studio_result(surface, {.mode = StudioMode::constant_wire});
  EXPECT_GT(wire.radius, 0);
  EXPECT_EQ(wire.radius, max_wire_radius(wire.curve.curves, 2));
  EXPECT_GT(wire.radius, checked.radius / 2); // the bound is within about a third of the truth
  EXPECT_LT(wire.radius, checked.radius * 2);
  EXPECT_EQ(checked.radius, auto_wire_radius(checked.curve.quads, checked.curve.cycle, {.curve = StudioParams{}.wire.curve.curve}));
  EXPECT_EQ(parse_make_request(R"({"session": "a", "preview": true})").params.preview, true);
  EXPECT_EQ(message_of(R"({"session": "a", "preview": 1})"), "preview: expected true or false, got 1");
}

// Bridges are the constant wire's, made in the full result (their union costs several
// times the wire): a preview, or another mode given the same settings, has none.
TEST(Studio, BridgesComeWithTheFullWires) {
  const StudioSurface surface = demo_surface();
  for (const StudioMode mode : {StudioMode::constant_wire, StudioMode::variable_wire}) {
    StudioParams params{.mode = mode};
    params.wire.bridges = 1.0;
    params.wire.levels = 0; // the control mesh: the same bridges, a fifth of the union's work
    const StudioResult bridged = make_studio_result(surface, params);
    EXPECT_GT(bridged.bridges.ends.size(), 100u);
    EXPECT_TRUE(bridged.report.watertight);
    EXPECT_FALSE(bridged.report.self_intersecting);
    const auto stats = nlohmann::json::parse(studio_stats_json(bridged));
    EXPECT_EQ(stats["millimetres"], false); // in the model's units
    EXPECT_EQ(stats["bridges"]["count"], bridged.bridges.ends.size());
    EXPECT_EQ(stats["bridges"]["every_pass_tied"], bridged.bridges.every_pass_tied);
    EXPECT_LE(stats["bridges"]["longest_stretch"].get<double>(), 1.0 + 1e-9);
  }
  StudioParams params{.mode = StudioMode::constant_wire};
  params.wire.bridges = 1.0;
  for (const StudioMode mode : {StudioMode::constant_wire, StudioMode::constant_ribbon, StudioMode::variable_wire,
                                StudioMode::variable_ribbon}) {
    StudioParams other = params;
    other.mode = mode;
    other.preview = mode == StudioMode::constant_wire || mode == StudioMode::variable_wire;
    const StudioResult plain = make_studio_result(surface, other);
    EXPECT_TRUE(plain.bridges.ends.empty());
    EXPECT_FALSE(nlohmann::json::parse(studio_stats_json(plain)).contains("bridges"));
  }
}

// A duotone with a shell (its wall in millimetres, with a model size) is also the
// two-colour print `meander duotone --shell -o OUT.3mf` writes; a preview has none, and
// a surface that cannot be thickened is still painted, the stats saying why.
TEST(Studio, ADuotoneWithAShellIsATwoColourPrint) {
  const StudioSurface surface = demo_surface();
  const MakeRequest request = parse_make_request(
      R"({"session": "x", "mode": "duotone", "model_size": "100mm", "shell": 1.5, "clearance": 0, "texture_size": 64})");
  ASSERT_EQ(request.params.duotone.shell, 1.5);
  EXPECT_EQ(parse_make_request(R"({"session": "x", "mode": "duotone", "shell": 1.5, "clearance": 0.3})").params.duotone.clearance, 0.3);
  const StudioResult painted = make_studio_result(surface, request.params);
  ASSERT_TRUE(painted.shell.has_value());
  EXPECT_GE(studio_result_size(surface, request.params),
            painted.triangles + painted.shell->solids[0].num_faces() + painted.shell->solids[1].num_faces());
  const auto stats = nlohmann::json::parse(studio_stats_json(painted));
  EXPECT_EQ(stats["millimetres"], true); // the page gives its lengths in mm
  ASSERT_EQ(stats["shell"]["volumes"].size(), 2u);
  EXPECT_GT(stats["shell"]["volumes"][0].get<double>(), 0);
  EXPECT_EQ(stats["shell"]["summary"], shell_summary(*painted.shell, painted.params.duotone));
  const StudioDownload print = studio_download(surface, painted, StudioFile::print);
  EXPECT_EQ(print.filename, "pretzel_duotone_print.3mf");
  const std::filesystem::path path = test::output_dir() / "studio_print.3mf";
  write_3mf_parts(colored_parts(painted.shell->solids[0], painted.shell->solids[1], painted.params.duotone.tiles.colors), path);
  EXPECT_TRUE(print.bytes == test::read_file(path));

  StudioParams preview = request.params;
  preview.preview = true;
  preview.duotone.clearance = 0.1; // a preview has no print, nor its gap
  const StudioResult quick = make_studio_result(surface, preview);
  EXPECT_FALSE(quick.shell.has_value());
  EXPECT_FALSE(nlohmann::json::parse(studio_stats_json(quick)).contains("shell"));
  EXPECT_THROW(studio_download(surface, quick, StudioFile::print), UsageError);

  StudioSurface band{.name = "moebius.obj"};
  band.repaired = repair(make_shape("moebius", 400), band.name);
  const StudioResult unprintable = make_studio_result(band, request.params);
  EXPECT_FALSE(unprintable.shell.has_value());
  EXPECT_FALSE(unprintable.mesh.positions.empty()); // still painted
  const std::string refused = nlohmann::json::parse(studio_stats_json(unprintable))["shell"]["refused"];
  EXPECT_NE(refused.find("not orientable"), std::string::npos) << refused;
  try {
    studio_download(band, unprintable, StudioFile::print);
    ADD_FAILURE() << "a print without a shell";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("not orientable"), std::string::npos) << e.what();
  }
}

// A constant preview with `radius auto` after a full result on the same curve takes that
// result's checked radius (another slider, here the sides, is moving), so that it is as
// thick as what follows; on another curve (a new seed) it takes the bound on its own curve.
TEST(Studio, AConstantPreviewKeepsTheFullResultsRadiusOnTheSameCurve) {
  const StudioSurface surface = demo_surface();
  const StudioResult full = make_studio_result(surface, {.mode = StudioMode::constant_wire});
  ASSERT_GT(full.radius, 0);
  StudioParams sides{.mode = StudioMode::constant_wire, .wire = {.sides = 5}, .preview = true};
  const StudioResult same = make_studio_result(surface, sides, &full);
  EXPECT_EQ(same.radius, full.radius);
  EXPECT_EQ(same.params.wire.sides, 5);
  EXPECT_NE(make_studio_result(surface, sides).radius, full.radius);
  StudioParams reseeded = sides;
  reseeded.wire.curve.cycle.seed = 9;
  const StudioResult other = make_studio_result(surface, reseeded, &full);
  EXPECT_EQ(other.radius, max_wire_radius(other.curve.curves, 2));
  StudioParams spaced = sides; // another spacing is another curve too
  spaced.wire.curve.spacing = 0.5;
  const StudioResult remeshed = make_studio_result(surface, spaced, &full);
  EXPECT_EQ(remeshed.radius, max_wire_radius(remeshed.curve.curves, 2));
  // Only a full result lends its radius, and only to the same mode.
  const StudioResult after_preview = make_studio_result(surface, sides, &same);
  EXPECT_EQ(after_preview.radius, max_wire_radius(after_preview.curve.curves, 2));
  StudioParams ribbon = sides;
  ribbon.mode = StudioMode::constant_ribbon;
  const StudioResult band = make_studio_result(surface, ribbon, &full);
  EXPECT_EQ(band.radius, max_wire_radius(band.curve.curves, 2));
}

// A wire's own slider (s, t, thickness, sides, radius) keeps the curve of the result
// before when the same job made it; anything that changes the curve makes its own. The
// result before is given a moved curve, so that the test sees which one was taken.
TEST(Studio, AWiresSliderKeepsTheCurveOfTheResultBefore) {
  const StudioSurface surface = demo_surface();
  StudioParams ribbon{.mode = StudioMode::variable_ribbon, .preview = true};
  ribbon.wire.levels = 0;
  StudioResult before = make_studio_result(surface, ribbon);
  for (Vec3& p : before.curve.curves.points) p = p + Vec3{1, 0, 0};
  StudioParams wider = ribbon;
  wider.wire.s = 0.3;
  EXPECT_EQ(make_studio_result(surface, wider, &before).curve.curves.points, before.curve.curves.points);
  const StudioResult fresh = make_studio_result(surface, wider);
  EXPECT_NE(fresh.curve.curves.points, before.curve.curves.points);
  StudioParams reseeded = wider, spaced = wider, wire = wider, full = wider;
  reseeded.wire.curve.cycle.seed = 9;
  spaced.wire.curve.spacing = 0.5;
  wire.mode = StudioMode::constant_ribbon; // a curve without the variable wire's slab mesh
  full.preview = false;                    // more samples and a relaxed curve
  full.wire.report = false;
  for (const StudioParams& other : {reseeded, spaced, wire, full})
    EXPECT_EQ(make_studio_result(surface, other, &before).curve.curves.points, make_studio_result(surface, other).curve.curves.points);
}

// A result of a spacing keeps the even surface of the result before when it was made for
// the same spacing, model size and quad (a seed, a mode, a preview's release), and makes
// what a fresh result would; another spacing remeshes. The result before is given a
// moved even surface, so that the test sees which one was taken.
TEST(Studio, ASpacingsEvenSurfaceIsKeptWhileOtherSlidersMove) {
  const StudioSurface surface = demo_surface();
  StudioParams curve{.mode = StudioMode::curve, .preview = true};
  curve.wire.curve.spacing = 0.5;
  const StudioResult first = make_studio_result(surface, curve);
  ASSERT_TRUE(first.even);
  EXPECT_EQ(first.even->options, even_surface_options(curve.wire.curve));
  StudioResult before = first;
  EvenSurface moved = make_even_surface(surface.repaired.mesh, first.even->options);
  for (Vec3& p : moved.even.positions) p = p + Vec3{1, 0, 0};
  before.even = std::make_shared<const EvenSurface>(std::move(moved));
  StudioParams reseeded = curve, wire = curve, full = curve, duotone{.mode = StudioMode::duotone, .preview = true};
  reseeded.wire.curve.cycle.seed = 9;
  wire.mode = StudioMode::variable_ribbon;
  full.preview = false;
  duotone.duotone.spacing = 0.5;
  duotone.duotone.duotone.quadrangulation = Quadrangulation::dual_simplest; // the curve's: the same even surface
  for (const StudioParams& same : {reseeded, wire, full, duotone}) {
    const StudioResult kept = make_studio_result(surface, same, &before);
    EXPECT_EQ(kept.even, before.even) << int(same.mode);
    // The curve was made on it (the moved surface's quads), else the same as a fresh one.
    const StudioResult fresh = make_studio_result(surface, same);
    EXPECT_NE(kept.curve.quads.positions, fresh.curve.quads.positions);
    EXPECT_EQ(make_studio_result(surface, same, &first).curve.curves.points, fresh.curve.curves.points);
  }
  StudioParams other = curve;
  other.wire.curve.spacing = 0.4;
  const StudioResult remeshed = make_studio_result(surface, other, &before);
  EXPECT_NE(remeshed.even, before.even);
  EXPECT_EQ(remeshed.even->options.spacing, 0.4);
  EXPECT_FALSE(make_studio_result(surface, {.mode = StudioMode::curve}, &first).even); // no spacing, no even surface
}

TEST(Studio, UploadsOverTheFaceLimitAreRefused) {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  EXPECT_EQ(load_studio_surface("square.obj", square, 2).input_faces, 2);
  try {
    load_studio_surface("square.obj", square, 1);
    FAIL() << "2 faces passed a limit of 1";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "square.obj: 2 faces, more than the limit of 1");
  }
}

TEST(Studio, ViewBytesHoldTheFacesAndSegments) {
  PolygonMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
  mesh.add_face({0, 1, 2, 3});       // a quad as 2 triangles
  mesh.add_face({1, 4, 5});          // a triangle as a triangle
  mesh.add_face({2, 1, 5, 6, 7});    // a pentagon fanned into 3 triangles
  Polylines loop;
  loop.points = {{0, 0, 1}, {1, 0, 1}, {0, 1, 2}};
  loop.start = {0, 3};
  const test::DecodedView view = test::decode_view(studio_view_bytes(mesh, loop));
  ASSERT_TRUE(view.ok);
  EXPECT_EQ(std::vector<uint32_t>({view.vertices, view.triangles, view.segments, view.flags}),
            (std::vector<uint32_t>{11, 6, 3, 2})); // normals, no texture
  EXPECT_EQ(std::vector<float>(view.box, view.box + 6), (std::vector<float>{0, 0, 0, 2, 2, 2})); // the curve's points too
  // The curve's second point, after the 8 of the mesh, within a step (2 / 65535) of (1, 0, 1).
  EXPECT_NEAR(view.positions[3 * 9 + 0], 1.0f, 2.0 / 65535);
  EXPECT_NEAR(view.positions[3 * 9 + 2], 1.0f, 2.0 / 65535);
  // The faces all face +z: every mesh vertex's normal is (0, 0, 127); the curve's points have none.
  for (size_t v = 0; v < 11; ++v)
    EXPECT_EQ(std::vector<int>(view.normals.begin() + 4 * v, view.normals.begin() + 4 * v + 4),
              (std::vector<int>{0, 0, v < 8 ? 127 : 0, 0}))
        << v;
  // meshoptimizer's index codec keeps each triangle and their order, and may rotate a
  // triangle's corners: compared as the sets of corners, in order.
  std::vector<std::vector<uint32_t>> triangles;
  for (size_t t = 0; t < 6; ++t) {
    std::vector<uint32_t> corners(view.triangle_indices.begin() + 3 * t, view.triangle_indices.begin() + 3 * t + 3);
    std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
    triangles.push_back(corners);
  }
  EXPECT_EQ(triangles, (std::vector<std::vector<uint32_t>>{{0, 1, 2}, {0, 2, 3}, /* triangle */ {1, 4, 5},
                                                           /* fan */ {1, 5, 2}, {2, 5, 6}, {2, 6, 7}}));
  EXPECT_EQ(view.segment_indices, (std::vector<uint32_t>{8, 9, 9, 10, 10, 8})); // 8 mesh vertices, then the curve's
  // A curve alone has neither normals nor texture coordinates.
  const test::DecodedView curve = test::decode_view(studio_view_bytes({}, loop));
  EXPECT_TRUE(curve.ok);
  EXPECT_EQ(curve.flags, 0u);
  EXPECT_EQ(curve.triangles, 0u);
  // With texture coordinates every face corner is a vertex of its own.
  PolygonMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.add_face({0, 1, 2, 3});
  Appearance appearance{.materials = {{.name = "m"}}, .texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  const test::DecodedView textured = test::decode_view(studio_view_bytes(quad, {}, appearance));
  ASSERT_TRUE(textured.ok);
  EXPECT_EQ(textured.vertices, 4u);
  EXPECT_EQ(textured.flags, 3u);
  EXPECT_EQ(textured.texcoords[4], 1.0f); // corner 2 is (1, 1)
  EXPECT_EQ(textured.texcoords[5], 1.0f);
}

// Whatever the numbering of its vertices (first use; with texture coordinates, each
// distinct (vertex, texture coordinate) pair of the corners), the view draws the result's
// triangles, in order, each corner at its position (within a quantization step) with its
// texture coordinate (within a 16-bit step): a duotone (textured quads) and a ribbon.
TEST(Studio, TheViewDrawsTheResultsTrianglesCornerByCorner) {
  const StudioSurface surface = demo_surface();
  for (const StudioMode mode : {StudioMode::duotone, StudioMode::variable_ribbon}) {
    StudioParams params;
    params.mode = mode;
    params.wire.levels = 0;
    params.duotone.subdivide = 0;
    params.duotone.tiles.texture_size = 64;
    const StudioResult result = make_studio_result(surface, params);
    const PolygonMesh& mesh = result.mesh;
    const std::vector<TexCoord>& uv = result.appearance.texcoords;
    const bool textured = mode == StudioMode::duotone;
    ASSERT_EQ(!uv.empty(), textured);
    const test::DecodedView view = test::decode_view(studio_view_bytes(mesh, {}, result.appearance));
    ASSERT_TRUE(view.ok);
    // Fewer vertices than corners where corners share them.
    EXPECT_LT(view.vertices, textured ? mesh.face_vertices.size() : mesh.positions.size() + 1) << int(mode);
    const float step = std::max({view.box[3] - view.box[0], view.box[4] - view.box[1], view.box[5] - view.box[2]}) / 65535;
    size_t t = 0, mismatches = 0;
    for (int32_t f = 0; f < mesh.num_faces(); ++f)
      for (int32_t i = 1; i + 1 < mesh.face_size(f); ++i, ++t) {
        ASSERT_LT(t, size_t(view.triangles));
        const std::array<int32_t, 3> corners{mesh.face_start[f], mesh.face_start[f] + i, mesh.face_start[f] + i + 1};
        // The index codec may rotate a triangle's corners: find the rotation.
        bool found = false;
        for (int r = 0; r < 3 && !found; ++r) {
          found = true;
          for (int k = 0; k < 3 && found; ++k) {
            const int32_t c = corners[size_t((k + r) % 3)];
            const uint32_t drawn = view.triangle_indices[3 * t + size_t(k)];
            const Vec3 p = mesh.positions[size_t(mesh.face_vertices[size_t(c)])];
            const float expected[3] = {p.x, p.y, p.z};
            for (size_t a = 0; a < 3; ++a) found = found && std::abs(view.positions[3 * drawn + a] - expected[a]) <= step;
            if (textured)
              found = found && std::abs(view.texcoords[2 * drawn] - uv[size_t(c)].u) <= 1.0f / 65535 &&
                      std::abs(view.texcoords[2 * drawn + 1] - uv[size_t(c)].v) <= 1.0f / 65535;
          }
        }
        mismatches += !found;
      }
    EXPECT_EQ(t, size_t(view.triangles)) << int(mode);
    EXPECT_EQ(mismatches, 0u) << int(mode) << ": triangles whose corners the view moved";
  }
}

// render.png as the page's view shows it: its size, and its camera.
TEST(Studio, ThePictureTakesTheViewsSizeAndCamera) {
  const StudioSurface surface = demo_surface();
  const StudioResult curve = make_studio_result(surface, {});
  const StudioPicture picture = parse_studio_picture(
      {{"size", "160x100"}, {"eye", "0,0,20"}, {"target", "0,0,0"}, {"up", "0,1,0"}, {"fov", "35"}});
  ASSERT_TRUE(picture.camera.has_value());
  EXPECT_EQ(picture.camera->eye.z, 20);
  EXPECT_EQ(picture.camera->fov_degrees, 35);
  const Texture front = read_texture(studio_download(surface, curve, StudioFile::png, picture).bytes, "render.png");
  EXPECT_EQ(front.width, 160);
  EXPECT_EQ(front.height, 100);
  // Much farther away, the model covers far fewer pixels.
  const auto covered = [](const Texture& t) {
    size_t n = 0;
    for (size_t i = 0; i + 3 < t.rgba.size(); i += 4) n += t.rgba[i] < 250 || t.rgba[i + 1] < 250 || t.rgba[i + 2] < 250;
    return n;
  };
  const Texture far = read_texture(
      studio_download(surface, curve, StudioFile::png, parse_studio_picture({{"size", "160x100"}, {"eye", "0,0,80"}, {"target", "0,0,0"}}))
          .bytes,
      "render.png");
  EXPECT_GT(covered(front), 4 * covered(far));
  EXPECT_GT(covered(far), 0u);
  for (const std::multimap<std::string, std::string>& bad :
       std::vector<std::multimap<std::string, std::string>>{{{"eye", "0,0,1"}}, {{"eye", "1,2"}, {"target", "0,0,0"}},
                                                            {{"size", "0x10"}}, {{"fov", "180"}}, {{"zoom", "2"}}})
    EXPECT_THROW(parse_studio_picture(bad), UsageError) << bad.begin()->first;
  EXPECT_THROW(studio_download(surface, curve, StudioFile::png, parse_studio_picture({{"eye", "1,1,1"}, {"target", "1,1,1"}})),
               UsageError);
}

TEST(Studio, ResultFilesHaveFixedNames) {
  EXPECT_EQ(parse_studio_file("result.stl"), StudioFile::stl);
  for (const char* bad : {"../result.stl", "result.stl/", "/etc/passwd", "", "RESULT.STL", "result.stl.."})
    EXPECT_THROW(parse_studio_file(bad), UsageError) << bad;
}

// Made in memory, byte for byte what the CLI's writers put in files.
TEST(Studio, DownloadsAreTheWritersFiles) {
  const StudioSurface surface = demo_surface();
  const std::filesystem::path dir = test::output_dir();
  const StudioResult wire = make_studio_result(surface, {.mode = StudioMode::variable_wire, .wire = {.levels = 0}});
  const StudioDownload stl = studio_download(surface, wire, StudioFile::stl);
  uint32_t triangles = 0;
  std::memcpy(&triangles, stl.bytes.data() + 80, 4);
  EXPECT_EQ(triangles, wire.report.triangles);
  EXPECT_EQ(stl.bytes.size(), 84 + 50 * size_t(triangles));
  EXPECT_EQ(stl.filename, "pretzel_variable-wire.stl");
  for (const auto& [file, name] : {std::pair{StudioFile::stl, "w.stl"}, {StudioFile::threemf, "w.3mf"}, {StudioFile::glb, "w.glb"}}) {
    write_mesh(wire.mesh, dir / name);
    EXPECT_TRUE(studio_download(surface, wire, file).bytes == test::read_file(dir / name)) << name;
  }
  const StudioDownload zip = studio_download(surface, wire, StudioFile::obj_zip);
  EXPECT_EQ(zip.bytes.substr(0, 4), std::string("PK\3\4", 4));
  EXPECT_NE(zip.bytes.find("pretzel_variable-wire.mtl"), std::string::npos);
  EXPECT_NE(zip.bytes.find("mtllib pretzel_variable-wire.mtl"), std::string::npos); // stored, so readable
  // A zip reader finds the OBJ and its MTL, and the same files give the same archive.
  const std::map<std::string, std::string> files = unzip(zip.bytes);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_NE(files.at("pretzel_variable-wire.obj").find("mtllib pretzel_variable-wire.mtl"), std::string::npos);
  EXPECT_TRUE(files.contains("pretzel_variable-wire.mtl"));
  EXPECT_EQ(studio_download(surface, wire, StudioFile::obj_zip).bytes, zip.bytes);
  // The render as `meander wire --png` draws it: 1200 x 900, the copper wire covering a good part of it.
  const Texture picture = read_texture(studio_download(surface, wire, StudioFile::png).bytes, "render.png");
  EXPECT_EQ(picture.width, 1200);
  EXPECT_EQ(picture.height, 900);
  size_t copper = 0;
  for (size_t i = 0; i + 3 < picture.rgba.size(); i += 4)
    copper += picture.rgba[i] > picture.rgba[i + 2] + 60 && picture.rgba[i] > picture.rgba[i + 1];
  EXPECT_GT(copper, picture.rgba.size() / 4 / 20);
  // A duotone's zip carries its texture, as `meander duotone -o x.obj` writes it.
  StudioParams duotone{.mode = StudioMode::duotone};
  duotone.duotone.tiles.texture_size = 64;
  const StudioResult painted = make_studio_result(surface, duotone);
  const StudioDownload painted_zip = studio_download(surface, painted, StudioFile::obj_zip);
  EXPECT_NE(painted_zip.bytes.find("pretzel_duotone_texture.png"), std::string::npos);
  const TexturedMesh textured{.mesh = painted.mesh, .appearance = painted.appearance};
  write_textured_mesh(textured, dir / "pretzel_duotone.obj");
  EXPECT_NE(painted_zip.bytes.find(test::read_file(dir / "pretzel_duotone.obj")), std::string::npos);
  write_textured_mesh(textured, dir / "d.glb");
  EXPECT_TRUE(studio_download(surface, painted, StudioFile::glb).bytes == test::read_file(dir / "d.glb"));
  const std::string texture = studio_download(surface, painted, StudioFile::texture).bytes;
  EXPECT_TRUE(texture == test::read_file(dir / "pretzel_duotone_texture.png"));
  EXPECT_THROW(studio_download(surface, wire, StudioFile::texture), UsageError);
  const StudioResult curve = make_studio_result(surface, {});
  EXPECT_THROW(studio_download(surface, curve, StudioFile::glb), UsageError);
  EXPECT_TRUE(studio_download(surface, curve, StudioFile::svg).bytes == curve_svg(curve.curve, false));
  // With the page's camera, the plotter drawing of its view, on A4 turned as the view is.
  const CameraPose seen{.eye = {4, 1, 6}, .target = {0, 0, 0}};
  const std::string drawn = studio_download(surface, curve, StudioFile::svg, {.width = 800, .height = 500, .camera = seen}).bytes;
  EXPECT_TRUE(drawn == drawing_svg(draw_curve(curve.curve, {.camera = seen, .paper = parse_paper("A4", true)}), 0.3));
  EXPECT_NE(drawn.find(R"(width="297mm" height="210mm")"), std::string::npos);
}

// What `work` throws as E, or a note that it threw nothing.
template <class E, class Work> std::string thrown(Work&& work) {
  try {
    work();
  } catch (const E& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

// A dark disk on white as PNG bytes, w x h pixels.
std::string disk_png(int32_t w, int32_t h) {
  Image image{.width = w, .height = h};
  for (int32_t y = 0; y < h; ++y)
    for (int32_t x = 0; x < w; ++x) {
      const uint8_t g = std::hypot(x - w / 2.0, y - h / 2.0) < 0.35 * std::min(w, h) ? 20 : 235;
      image.rgba.insert(image.rgba.end(), {g, g, g, 255});
    }
  return png_file_bytes(image);
}

// Picture mode is `meander image`: the same parameters give the CLI's files byte for byte.
TEST(Studio, APictureIsDrawnAsMeanderImageDrawsIt) {
  const std::filesystem::path dir = test::output_dir();
  const std::string png = disk_png(160, 120);
  test::write_file("photo.png", png);
  const StudioSurface surface = load_studio_surface("uploads/photo.PNG", png);
  EXPECT_EQ(surface.name, "photo.PNG");
  EXPECT_EQ(surface.picture.width, 160);
  EXPECT_EQ(surface.repaired.mesh.num_faces(), 0);
  const MakeRequest request = parse_make_request(R"({"session": "s", "mode": "picture", "paper": "A5", "margin": "5mm",
      "spacing": 0.8, "max_spacing": 5, "gamma": 1.2, "seed": 3, "colors": "red,navy", "quad": "none", "radius": "auto"})");
  EXPECT_EQ(request.params.image.paper.width, 148);
  EXPECT_EQ(request.params.image.paper.margin, 5);
  EXPECT_EQ(request.params.image.tone.spacing, 0.8);
  EXPECT_EQ(request.params.image.cycle.seed, 3u);
  const StudioResult result = make_studio_result(surface, request.params);
  ASSERT_EQ(result.curve.curves.start.size(), 2u); // one closed line
  const json stats = json::parse(studio_stats_json(result));
  EXPECT_EQ(stats["mode"], "picture");
  EXPECT_EQ(stats["curves"], 1);
  EXPECT_EQ(stats["cells"], result.picture.cells);
  EXPECT_EQ(stats["paper"], json({210.0, 148.0})); // turned to the picture
  EXPECT_GT(stats["leaves"].get<int64_t>(), 0);
  EXPECT_NEAR(stats["curve_length"].get<double>(), result.picture.drawing.drawn_length, 1e-9);

  const auto out = [&](const char* name) { return (dir / name).string(); };
  const test::CommandResult r =
      test::run_cli({"image", out("photo.png"), "-o", out("photo_cli.svg"), "--paper", "A5", "--margin", "5mm", "--spacing",
                     "0.8", "--max-spacing", "5", "--gamma", "1.2", "--seed", "3", "--colors", "red,navy", "--duotone",
                     out("photo_cli_duotone.svg"), "--png", out("photo_cli.png"), "--size", "400x300"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(test::run_cli({"image", out("photo.png"), "-o", out("photo_cli.obj"), "--paper", "A5", "--margin", "5mm",
                           "--spacing", "0.8", "--max-spacing", "5", "--gamma", "1.2", "--seed", "3"})
                .exit_code,
            0);
  const StudioDownload svg = studio_download(surface, result, StudioFile::svg, {.width = 400, .height = 300});
  EXPECT_EQ(svg.filename, "photo_picture.svg");
  EXPECT_TRUE(svg.bytes == test::read_file(out("photo_cli.svg")));
  EXPECT_TRUE(studio_download(surface, result, StudioFile::duotone_svg).bytes == test::read_file(out("photo_cli_duotone.svg")));
  EXPECT_TRUE(studio_download(surface, result, StudioFile::png, {.width = 400, .height = 300}).bytes ==
              test::read_file(out("photo_cli.png")));
  const std::map<std::string, std::string> zip = unzip(studio_download(surface, result, StudioFile::obj_zip).bytes);
  ASSERT_EQ(zip.size(), 1u);
  EXPECT_TRUE(zip.at("photo_picture.obj") == test::read_file(out("photo_cli.obj")));

  // A preview: the same line with at most 2 samples a segment.
  StudioParams preview = request.params;
  preview.preview = true;
  preview.duotone.clearance = 0.1; // a preview has no print, nor its gap
  const StudioResult quick = make_studio_result(surface, preview);
  EXPECT_EQ(quick.params.image.curve.samples, 2);
  EXPECT_LT(quick.curve.curves.points.size(), result.curve.curves.points.size());
  EXPECT_EQ(studio_download(surface, quick, StudioFile::svg).filename, "photo_picture_preview.svg");
}

// A picture takes picture mode alone, a mesh every mode but picture: a clear refusal
// either way, and the files a picture has no use for.
TEST(Studio, APictureTakesPictureModeAlone) {
  const StudioSurface picture = load_studio_surface("photo.jpg.png", disk_png(40, 30));
  const StudioSurface mesh = demo_surface();
  EXPECT_EQ(thrown<UsageError>([&] { make_studio_result(picture, {.mode = StudioMode::curve}); }),
            "photo.jpg.png: a picture: only picture mode draws it (open a mesh for the other modes)");
  EXPECT_EQ(thrown<UsageError>([&] { make_studio_result(mesh, {.mode = StudioMode::picture}); }),
            "pretzel.obj: a mesh: picture mode draws a picture (open a .png or .jpg)");
  const StudioResult drawn = make_studio_result(picture, {.mode = StudioMode::picture});
  EXPECT_THROW(studio_download(picture, drawn, StudioFile::surface), UsageError);
  EXPECT_THROW(studio_download(picture, drawn, StudioFile::stl), UsageError);
  EXPECT_THROW(studio_download(picture, drawn, StudioFile::texture), UsageError);
  EXPECT_THROW(studio_download(mesh, make_studio_result(mesh, {}), StudioFile::duotone_svg), UsageError);
  EXPECT_EQ(parse_studio_file("duotone.svg"), StudioFile::duotone_svg);
  // The CLI's refusals, naming the upload.
  EXPECT_EQ(thrown<InputError>([&] { make_studio_result(load_studio_surface("dot.png", disk_png(1, 1)), {.mode = StudioMode::picture}); }),
            "dot.png: a picture of 1x1 pixels has no tones to draw (at least 2x2)");
  EXPECT_THROW(load_studio_surface("big.png", disk_png(40, 30), 0, 1199), InputError);
  EXPECT_THROW(load_studio_surface("broken.png", "not a png"), InputError);
  // A picture's lengths are millimetres on paper: units need no model size there.
  EXPECT_EQ(parse_make_request(R"({"session": "s", "mode": "picture", "spacing": "1mm", "pen": "0.05cm"})").params.image.pen, 0.5);
  EXPECT_TRUE(parse_make_request(R"({"session": "s", "mode": "picture", "invert": true})").params.image.tone.invert);
  EXPECT_NE(message_of(R"({"session": "s", "mode": "picture", "gamma": 20})").find("gamma"), std::string::npos);
  EXPECT_EQ(message_of(R"({"session": "s", "mode": "picture", "max_pixels": 20})"), "\"max_pixels\": unknown parameter");
}

// What a server checks before any work bounds the line a picture mode makes: a black
// picture has the most ink there is.
TEST(Studio, APicturesResultSizeBoundsItsLine) {
  Image black{.width = 30, .height = 20, .rgba = std::vector<uint8_t>(30 * 20 * 4, 0)};
  for (size_t i = 3; i < black.rgba.size(); i += 4) black.rgba[i] = 255;
  const StudioSurface surface = load_studio_surface("black.png", png_file_bytes(black));
  for (const char* sheet : {R"("paper": "A5")", R"("width": "60mm", "margin": 0)"}) {
    const StudioParams params = parse_make_request(std::string(R"({"session": "s", "mode": "picture", "spacing": 1.5, )") + sheet + "}").params;
    const StudioResult result = make_studio_result(surface, params);
    const int64_t points = int64_t(result.curve.curves.points.size());
    EXPECT_LE(points, studio_result_size(surface, params)) << sheet;
    EXPECT_GE(points, studio_result_size(surface, params) / 3) << sheet;
  }
}

TEST(Studio, SessionsAreFoundByIdAndTheOldestDropped) {
  StudioSessions sessions(2);
  const std::string a = sessions.add(demo_surface()).id;
  EXPECT_EQ(a.size(), 32u);
  EXPECT_NE(sessions.find(a), nullptr);
  EXPECT_EQ(sessions.find("../" + a), nullptr);
  const std::string b = sessions.add(demo_surface()).id, c = sessions.add(demo_surface()).id;
  EXPECT_NE(a, b);
  EXPECT_EQ(sessions.find(a), nullptr);
  EXPECT_NE(sessions.find(b), nullptr);
  EXPECT_NE(sessions.find(c), nullptr);
  // The caller keeps the session it added even when it is dropped before it can look it
  // up (100 concurrent uploads into 32 sessions crashed the server that way).
  StudioSessions one(1);
  const StudioSessions::Added first = one.add(demo_surface());
  one.add(demo_surface());
  EXPECT_EQ(one.find(first.id), nullptr);
  ASSERT_NE(first.session, nullptr);
  EXPECT_EQ(first.session->surface->input_faces, demo_surface().input_faces);
}

} // namespace
} // namespace meander
