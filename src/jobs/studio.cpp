#include "meander/studio.h"

#include "io/binary.h"
#include "io/zip.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/textured_io.h"
#include "meander/render.h"
#include "meander/shapes.h"
#include "meander/subdivide.h"
#include "meander/wire.h"

#include "io/image_codec.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>

namespace meander {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A make request is a few hundred bytes; anything far larger is not one.
constexpr size_t max_request_bytes = 64 * 1024;

std::string describe(const json& value) {
  std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  return text.size() > 40 ? text.substr(0, 40) + "..." : text;
}

double number_in(const json& value, const char* key, double lo, double hi) {
  if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() < lo || value.get<double>() > hi) {
    std::ostringstream range;
    range << (std::isinf(hi) ? "a number >= " : "a number in [") << lo;
    if (!std::isinf(hi)) range << ", " << hi << "]";
    throw UsageError(std::string(key) + ": expected " + range.str() + ", got " + describe(value));
  }
  return value.get<double>();
}

int integer_in(const json& value, const char* key, int lo, int hi) {
  if (!value.is_number_integer() || value.get<int64_t>() < lo || value.get<int64_t>() > hi)
    throw UsageError(std::string(key) + ": expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "], got " + describe(value));
  return int(value.get<int64_t>());
}

std::string text(const json& value, const char* key) {
  if (!value.is_string()) throw UsageError(std::string(key) + ": expected a string, got " + describe(value));
  return value.get<std::string>();
}

// The named parser's refusal, prefixed with the key it came from.
template <class Parse> auto named(const char* key, Parse parse) {
  try {
    return parse();
  } catch (const UsageError& e) {
    throw UsageError(std::string(key) + ": " + e.what());
  }
}

// tinygltf resolves a glTF's buffer and image URIs as files beside it; an upload has no
// folder of its own, so any URI other than data: would read the server's files.
void refuse_external_uris(std::string_view bytes, const std::string& name) {
  std::string_view json_text = bytes;
  if (bytes.starts_with("glTF")) {
    if (bytes.size() < 20) throw InputError(name + ": GLB header: file too short (" + std::to_string(bytes.size()) + " bytes)");
    const uint32_t length = io::load_little_endian<uint32_t>(bytes.data() + 12);
    if (bytes.substr(16, 4) != "JSON" || length > bytes.size() - 20)
      throw InputError(name + ": GLB: the first chunk is not a JSON chunk within the file");
    json_text = bytes.substr(20, length);
  }
  const json document = json::parse(json_text, nullptr, false);
  if (document.is_discarded() || !document.is_object()) throw InputError(name + ": glTF JSON does not parse as an object");
  for (const char* kind : {"buffers", "images"}) {
    const auto list = document.find(kind);
    if (list == document.end() || !list->is_array()) continue;
    for (size_t i = 0; i < list->size(); ++i) {
      const json& item = (*list)[i];
      if (!item.is_object() || !item.contains("uri")) continue;
      const json& uri = item["uri"];
      if (!uri.is_string() || !uri.get<std::string>().starts_with("data:"))
        throw InputError(name + ": " + std::string(kind).substr(0, std::strlen(kind) - 1) + " " + std::to_string(i) +
                         " refers to the file " + describe(uri) +
                         ": an uploaded glTF must embed its data (GLB or data: URIs)");
    }
  }
}

std::string sanitized(std::string_view text) {
  std::string out;
  for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  return out.empty() ? "meander" : out;
}

std::string mode_name(StudioMode mode) {
  switch (mode) {
  case StudioMode::curve: return "curve";
  case StudioMode::constant_wire: return "constant-wire";
  case StudioMode::constant_ribbon: return "constant-ribbon";
  case StudioMode::variable_wire: return "variable-wire";
  case StudioMode::variable_ribbon: return "variable-ribbon";
  case StudioMode::duotone: return "duotone";
  }
  return "curve";
}

std::string read_and_remove(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IOError(path.string() + ": cannot open the file just written");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  fs::remove(path);
  return bytes;
}

double total_length(const Polylines& curves) {
  double length = 0;
  for (size_t k = 0; k + 1 < curves.start.size(); ++k) {
    const int32_t begin = curves.start[k], end = curves.start[k + 1];
    for (int32_t i = begin; i + 1 < end; ++i) length += norm(curves.points[i + 1] - curves.points[i]);
    const bool open = !curves.open.empty() && curves.open[k];
    if (!open && end - begin > 1) length += norm(curves.points[begin] - curves.points[end - 1]);
  }
  return length;
}

bool is_wire(StudioMode mode) { return mode == StudioMode::constant_wire || mode == StudioMode::variable_wire; }

} // namespace

StudioMode parse_studio_mode(std::string_view name) {
  for (StudioMode mode : {StudioMode::curve, StudioMode::constant_wire, StudioMode::constant_ribbon,
                          StudioMode::variable_wire, StudioMode::variable_ribbon, StudioMode::duotone})
    if (name == mode_name(mode)) return mode;
  throw UsageError("unknown mode '" + std::string(name.substr(0, 40)) +
                   "' (expected curve, constant-wire, constant-ribbon, variable-wire, variable-ribbon or duotone)");
}

MakeRequest parse_make_request(std::string_view body) {
  if (body.size() > max_request_bytes)
    throw UsageError("request body of " + std::to_string(body.size()) + " bytes: a make request is at most " +
                     std::to_string(max_request_bytes));
  const json document = json::parse(body, nullptr, false);
  if (document.is_discarded()) throw UsageError("request body is not valid JSON");
  if (!document.is_object()) throw UsageError("request body: expected a JSON object, got " + describe(document));
  MakeRequest request;
  StudioParams& p = request.params;
  bool has_session = false;
  for (const auto& [key, value] : document.items()) {
    if (key == "session") {
      request.session = text(value, "session");
      has_session = true;
    } else if (key == "mode") {
      p.mode = named("mode", [&] { return parse_studio_mode(text(value, "mode")); });
    } else if (key == "quad") {
      p.job.quadrangulation = named("quad", [&] { return parse_quadrangulation(text(value, "quad")); });
    } else if (key == "tree") {
      p.job.cycle.tree = named("tree", [&] { return parse_tree_strategy(text(value, "tree")); });
    } else if (key == "smooth") {
      p.job.curve.smoothing = named("smooth", [&] { return parse_smoothing(text(value, "smooth")); });
    } else if (key == "seed") {
      if (!value.is_number_unsigned())
        throw UsageError("seed: expected a non-negative integer, got " + describe(value));
      p.job.cycle.seed = value.get<uint64_t>();
    } else if (key == "samples") {
      p.job.curve.samples = integer_in(value, "samples", 1, 1000);
    } else if (key == "radius") {
      if (value.is_string() && value.get<std::string>() == "auto")
        p.radius = 0;
      else if (value.is_number() && value.get<double>() > 0 && std::isfinite(value.get<double>()))
        p.radius = value.get<double>();
      else
        throw UsageError("radius: expected a positive number or \"auto\", got " + describe(value));
    } else if (key == "sides") {
      p.sides = integer_in(value, "sides", 3, 64);
    } else if (key == "s") {
      p.s = number_in(value, "s", 0, 1);
    } else if (key == "t") {
      p.t = number_in(value, "t", 0, 1);
    } else if (key == "thickness") {
      p.thickness = number_in(value, "thickness", 0, INFINITY);
    } else if (key == "levels") {
      p.levels = integer_in(value, "levels", 0, 6);
    } else if (key == "rule") {
      p.rule = named("rule", [&] { return parse_duotone_rule(text(value, "rule")); });
    } else if (key == "colors") {
      p.tiles.colors = named("colors", [&] { return parse_duotone_colors(text(value, "colors")); });
    } else if (key == "tiles") {
      p.tiles.style = named("tiles", [&] { return parse_tile_style(text(value, "tiles")); });
    } else if (key == "texture_size") {
      p.tiles.texture_size = integer_in(value, "texture_size", 64, 8192);
    } else if (key == "subdivide") {
      p.subdivide = integer_in(value, "subdivide", 0, 5);
    } else if (key == "preview") {
      if (!value.is_boolean()) throw UsageError("preview: expected true or false, got " + describe(value));
      p.preview = value.get<bool>();
    } else {
      throw UsageError(describe(json(key)) + ": unknown parameter");
    }
  }
  if (!has_session) throw UsageError("session: missing (upload a mesh first: POST /api/mesh)");
  return request;
}

StudioSurface load_studio_surface(std::string_view filename, std::string_view bytes, int64_t max_faces) {
  // Only the last component: a client's "../../x.obj" is a name for messages, not a path.
  const size_t slash = filename.find_last_of("/\\");
  std::string name(slash == std::string_view::npos ? filename : filename.substr(slash + 1));
  if (name.empty()) name = "upload";
  const MeshFormat format = mesh_format_from_path(name);
  if (format == MeshFormat::gltf) refuse_external_uris(bytes, name);
  PolygonMesh mesh = read_mesh(bytes, format, name);
  StudioSurface surface{.name = name, .input_vertices = mesh.num_vertices(), .input_faces = mesh.num_faces()};
  surface.repaired = repair(std::move(mesh), name, {.max_faces = max_faces});
  return surface;
}

StudioSurface demo_surface() {
  PolygonMesh mesh = make_shape("pretzel", 1600);
  StudioSurface surface{.name = "pretzel.obj", .input_vertices = mesh.num_vertices(), .input_faces = mesh.num_faces()};
  surface.repaired = repair(std::move(mesh), surface.name);
  return surface;
}

namespace {

// The elements make_studio_result would hold for these parameters as they are.
int64_t result_size(const StudioSurface& surface, const StudioParams& params) {
  const PolygonMesh& mesh = surface.repaired.mesh;
  const int64_t faces = mesh.num_faces(), corners = int64_t(mesh.face_vertices.size());
  const int32_t edges = surface.repaired.connectivity.num_edges();
  // Quads per quadrangulation (quadrangulate.h): one per edge, one per corner, the faces.
  const auto quads = [&](Quadrangulation q) {
    switch (q) {
    case Quadrangulation::dual_simplest: return edges > 0 ? int64_t(edges) : corners;
    case Quadrangulation::catmull_clark: return corners;
    case Quadrangulation::none: return faces;
    }
    return corners;
  };
  int64_t cycle = 2 * quads(params.job.quadrangulation); // triangles the cycle visits
  if (params.mode == StudioMode::variable_wire || params.mode == StudioMode::variable_ribbon) {
    // The slab mesh splits a polygon of n >= 5 sides into a star: n more edges (dual of
    // Simplest's quads), 2n more corners (Catmull-Clark's).
    const int star_sides = SlabMeshOptions{}.star_sides;
    const int64_t per_side = params.job.quadrangulation == Quadrangulation::catmull_clark ? 4 : 2;
    for (int32_t f = 0; f < mesh.num_faces(); ++f)
      if (mesh.face_size(f) >= star_sides) cycle += per_side * mesh.face_size(f);
  }
  switch (params.mode) {
  case StudioMode::duotone: {
    const int64_t texture = int64_t(params.tiles.texture_size) * params.tiles.texture_size / 2; // the atlas
    return 4 * quads(params.job.quadrangulation) * (int64_t(1) << (2 * params.subdivide)) + texture;
  }
  case StudioMode::curve: return cycle * params.job.curve.samples;
  case StudioMode::constant_wire:
  case StudioMode::constant_ribbon:
    return constant_wire_triangles(cycle, {.shape = params.mode == StudioMode::constant_wire ? WireShape::wire : WireShape::ribbon,
                                           .sides = params.sides,
                                           .curve = params.job.curve});
  case StudioMode::variable_wire:
  case StudioMode::variable_ribbon:
    return variable_wire_triangles(cycle, {.shape = params.mode == StudioMode::variable_wire ? WireShape::wire : WireShape::ribbon,
                                           .levels = params.levels});
  }
  return 0;
}

// A preview holds at most about this many elements when fewer curve samples can make it
// so: what the page gets onto the screen in about a quarter of a second here (a variable
// wire preview of 2.4M triangles, docs/benchmarks.md).
constexpr int64_t preview_budget = 2'500'000;

// What a preview actually makes (StudioParams::preview).
StudioParams effective(const StudioSurface& surface, StudioParams params) {
  if (!params.preview) return params;
  params.job.curve.samples = std::min(params.job.curve.samples, 2);
  params.levels = 0;
  params.subdivide = 0;
  while (params.job.curve.samples > 1 && result_size(surface, params) > preview_budget) --params.job.curve.samples;
  return params;
}

} // namespace

int64_t studio_result_size(const StudioSurface& surface, const StudioParams& requested) {
  return result_size(surface, effective(surface, requested));
}

StudioResult make_studio_result(const StudioSurface& surface, const StudioParams& requested, const StudioResult* previous) {
  const auto start = std::chrono::steady_clock::now();
  const StudioParams params = effective(surface, requested);
  StudioResult result{.params = params};
  const StudioMode mode = params.mode;
  if (mode == StudioMode::duotone) {
    Duotone duotone = make_duotone(surface.repaired.mesh, surface.repaired.connectivity,
                                   {.quadrangulation = params.job.quadrangulation, .rule = params.rule,
                                    .tree = params.job.cycle.tree, .seed = params.job.cycle.seed});
    const bool same_atlas = previous && previous->params.mode == StudioMode::duotone &&
                            previous->params.tiles == params.tiles && !previous->appearance.materials.empty();
    TexturedMesh painted = same_atlas ? duotone_surface(duotone, params.tiles, previous->appearance.materials[0].texture)
                                      : duotone_surface(duotone, params.tiles);
    if (params.subdivide > 0) painted = subdivide(painted, {.levels = params.subdivide});
    result.curve.curves = separating_curves(duotone, params.tiles.style);
    result.curve_length = total_length(result.curve.curves);
    result.curve.quads = std::move(duotone.quads);
    result.curve.cycle = std::move(duotone.cycle);
    result.mesh = std::move(painted.mesh);
    result.appearance = std::move(painted.appearance);
    for (int32_t f = 0; f < result.mesh.num_faces(); ++f) result.triangles += std::max(0, result.mesh.face_size(f) - 2);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
  const bool variable = mode == StudioMode::variable_wire || mode == StudioMode::variable_ribbon;
  CurveJob curve_job = params.job;
  if (variable) curve_job.slab_mesh = SlabMeshOptions{}; // as `meander wire --method variable`
  result.curve = make_curve(surface.repaired.mesh, surface.repaired.connectivity, curve_job);
  result.curve_length = total_length(result.curve.curves);
  const WireShape shape = is_wire(mode) ? WireShape::wire : WireShape::ribbon;
  bool known_clear = false; // variable_wire searched its result already
  if (mode == StudioMode::constant_wire || mode == StudioMode::constant_ribbon) {
    std::optional<double> radius; // none: auto, checked by constant_wire
    if (params.radius > 0) {
      radius = params.radius;
    } else if (params.preview) {
      // The check that grows the analytic bound costs more than the wire, so a preview
      // does without it: it takes the radius of the full result before it when that was
      // made on the same curve (another slider is moving), so that the preview is as
      // thick as the result that follows; else the bound on its own, coarser curve.
      const CurveJob& job = requested.job;
      const bool same_curve = previous && !previous->params.preview && previous->params.mode == mode &&
                              previous->params.radius == 0 && previous->radius > 0 &&
                              previous->params.job.quadrangulation == job.quadrangulation &&
                              previous->params.job.cycle.tree == job.cycle.tree && previous->params.job.cycle.seed == job.cycle.seed &&
                              previous->params.job.curve == job.curve;
      radius = same_curve ? previous->radius
                          : max_wire_radius(result.curve.curves, params.job.curve.smoothing == Smoothing::none ? 1 : params.job.curve.samples);
    }
    ConstantWire made;
    if (!radius || *radius > 0)
      made = constant_wire(result.curve.quads, result.curve.cycle,
                           {.shape = shape, .radius = radius, .sides = params.sides, .curve = params.job.curve});
    if (!(made.radius > 0))
      throw TopologyError(surface.name + ": the curve touches itself: no wire radius avoids a self-intersection");
    result.radius = made.radius;
    result.mesh = std::move(made.mesh);
  } else if (variable) {
    VariableWire made = variable_wire(result.curve.quads, result.curve.cycle,
                                      {.shape = shape, .s = params.s, .t = params.t, .thickness = params.thickness,
                                       .levels = params.levels});
    result.mesh = std::move(made.mesh);
    known_clear = made.clear;
  }
  if (mode == StudioMode::curve) {
    result.triangles = int64_t(result.curve.cycle.order.size());
  } else if (params.preview) {
    for (int32_t f = 0; f < result.mesh.num_faces(); ++f) result.triangles += std::max(0, result.mesh.face_size(f) - 2);
  } else {
    result.report = check_printability(result.mesh, {.known_clear = known_clear, .thickness = false});
    result.triangles = result.report.triangles;
    if (result.report.self_intersecting)
      result.surface_crossings = int32_t(crossing_cycle_triangles(result.curve.quads, result.curve.cycle).size());
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string studio_stats_json(const StudioResult& result) {
  const Polylines& curves = result.curve.curves;
  json stats = {{"mode", mode_name(result.params.mode)},
                {"preview", result.params.preview},
                {"triangles", result.triangles},
                {"curves", curves.start.size() - 1},
                {"curve_points", curves.points.size()},
                {"curve_length", result.curve_length},
                {"seconds", result.seconds}};
  if (result.params.mode == StudioMode::duotone) {
    stats["quads"] = result.curve.quads.num_quads();
    stats["faces"] = result.mesh.num_faces();
    // What the atlas depends on: the page fetches texture.png again only when it changes.
    const TileOptions& tiles = result.params.tiles;
    std::string texture(to_string(tiles.style));
    for (const Color8& c : tiles.colors) {
      char hex[9];
      std::snprintf(hex, sizeof hex, " #%02x%02x%02x", c[0], c[1], c[2]);
      texture += hex;
    }
    stats["texture"] = texture + " " + std::to_string(tiles.texture_size);
  } else if (result.params.mode != StudioMode::curve) {
    stats["vertices"] = result.mesh.num_vertices();
    stats["faces"] = result.mesh.num_faces();
    if (!result.params.preview) {
      const PrintabilityReport& r = result.report;
      stats["watertight"] = r.watertight;
      stats["self_intersecting"] = r.self_intersecting;
      stats["volume"] = r.volume;
      stats["printable"] = r.printable();
      stats["surface_crossings"] = result.surface_crossings;
    }
    stats["stars"] = result.curve.stars;
    stats["cap_flips"] = result.curve.cap_flips;
    stats["cap_cuts"] = result.curve.cap_cuts;
    stats["needle_collapses"] = result.curve.needle_collapses;
    if (result.radius > 0) stats["radius"] = result.radius;
    else stats["radius"] = nullptr;
  }
  return stats.dump();
}

StudioFile parse_studio_file(std::string_view name) {
  static constexpr std::pair<std::string_view, StudioFile> table[] = {
      {"surface.bin", StudioFile::surface}, {"view.bin", StudioFile::view},      {"texture.png", StudioFile::texture},
      {"result.stl", StudioFile::stl},
      {"result.3mf", StudioFile::threemf},  {"result.glb", StudioFile::glb},     {"result.zip", StudioFile::obj_zip},
      {"curve.svg", StudioFile::svg},       {"render.png", StudioFile::png}};
  for (const auto& [file_name, file] : table)
    if (name == file_name) return file;
  throw UsageError("no result file of that name (expected surface.bin, view.bin, texture.png, result.stl, result.3mf, "
                   "result.glb, result.zip, curve.svg or render.png)");
}

std::string studio_view_bytes(const PolygonMesh& mesh, const Polylines& curves, const Appearance& appearance) {
  const bool textured = !appearance.texcoords.empty();
  // Quads go as quads (the page splits them), a third fewer indices than two triangles.
  int64_t quads = 0, triangles = 0, segments = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    if (mesh.face_size(f) == 4) ++quads;
    else triangles += std::max(0, mesh.face_size(f) - 2);
  for (size_t k = 0; k + 1 < curves.start.size(); ++k) {
    const int32_t n = curves.start[k + 1] - curves.start[k];
    const bool open = !curves.open.empty() && curves.open[k];
    segments += n < 2 ? 0 : (open ? n - 1 : n);
  }
  const bool shaded = quads + triangles > 0;
  const int64_t mesh_vertices = textured ? int64_t(mesh.face_vertices.size()) : int64_t(mesh.positions.size());
  const int64_t vertices = mesh_vertices + int64_t(curves.points.size());
  if (vertices > UINT32_MAX || 4 * quads + 3 * triangles > UINT32_MAX || segments > UINT32_MAX)
    throw UsageError("result too large for the view (over 2^32 elements)");
  // The normals are computed here, not in the page: a JavaScript loop over millions of
  // triangles took longer than making a preview (docs/benchmarks.md).
  const std::vector<Vec3> normals = shaded ? vertex_normals(mesh) : std::vector<Vec3>{};
  const size_t v = size_t(vertices), normal_bytes = shaded ? (3 * v + 3) / 4 * 4 : 0;
  std::string out(48 + 12 * v + normal_bytes + (textured ? 8 * v : 0) + 16 * size_t(quads) + 12 * size_t(triangles) +
                      8 * size_t(segments),
                  '\0');
  char* at = out.data();
  auto put = [&at](auto value) {
    io::store_little_endian(at, value);
    at += sizeof(value);
  };
  auto put_vec = [&put](Vec3 p) { put(p.x), put(p.y), put(p.z); };
  std::memcpy(at, "MNDR", 4);
  at += 4;
  put(uint32_t(vertices));
  put(uint32_t(quads));
  put(uint32_t(triangles));
  put(uint32_t(segments));
  put(uint32_t((textured ? 1 : 0) | (shaded ? 2 : 0)));
  Box3 box = bounding_box(mesh.positions);
  for (const Vec3& p : curves.points) box.extend(p);
  put_vec(box.min), put_vec(box.max);
  // With texture coordinates, which belong to the corners, every corner is a vertex.
  auto corner_vertex = [&mesh](int32_t c) { return size_t(mesh.face_vertices[size_t(c)]); };
  if (textured) for (int32_t c = 0; c < mesh.num_corners(); ++c) put_vec(mesh.positions[corner_vertex(c)]);
  else for (const Vec3& p : mesh.positions) put_vec(p);
  for (const Vec3& p : curves.points) put_vec(p);
  if (shaded) {
    char* const normals_end = at + normal_bytes;
    auto put_normal = [&](Vec3 n) { // rounded half away from zero, without a libm call per component
      for (float x : {n.x, n.y, n.z}) *at++ = char(int8_t(x * 127.0f + (x < 0 ? -0.5f : 0.5f)));
    };
    if (textured) for (int32_t c = 0; c < mesh.num_corners(); ++c) put_normal(normals[corner_vertex(c)]);
    else for (const Vec3& n : normals) put_normal(n);
    at = normals_end; // the curve's points have no normal: zero, and the padding
  }
  if (textured) {
    for (const TexCoord& t : appearance.texcoords) put(t.u), put(t.v);
    at += 8 * curves.points.size(); // the curve's points: (0, 0)
  }
  // A corner's vertex number in the view.
  auto index = [&](int32_t c) { return uint32_t(textured ? size_t(c) : corner_vertex(c)); };
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    if (mesh.face_size(f) == 4)
      for (int32_t i = 0; i < 4; ++i) put(index(mesh.face_start[f] + i));
  // Other polygons fanned: corners (start, start + i, start + i + 1).
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    if (mesh.face_size(f) != 4)
      for (int32_t i = 1; i + 1 < mesh.face_size(f); ++i)
        for (int32_t c : {0, i, i + 1}) put(index(mesh.face_start[f] + c));
  const uint32_t base = uint32_t(mesh_vertices);
  for (size_t k = 0; k + 1 < curves.start.size(); ++k) {
    const int32_t begin = curves.start[k], end = curves.start[k + 1];
    if (end - begin < 2) continue;
    for (int32_t i = begin; i + 1 < end; ++i) put(base + uint32_t(i)), put(base + uint32_t(i + 1));
    if (curves.open.empty() || !curves.open[k]) put(base + uint32_t(end - 1)), put(base + uint32_t(begin));
  }
  return out;
}

StudioDownload studio_download(const StudioSurface& surface, const StudioResult& result, StudioFile file,
                               const fs::path& scratch, const std::string& stem) {
  // A preview's files say so in their names, so that a script's saved files tell it too.
  const std::string base = sanitized(fs::path(surface.name).stem().string()) + "_" + mode_name(result.params.mode) +
                           (result.params.preview ? "_preview" : "");
  const bool curve_mode = result.params.mode == StudioMode::curve;
  const bool textured = !result.appearance.materials.empty();
  auto written_mesh = [&](const char* extension, const char* type) {
    if (curve_mode)
      throw UsageError(std::string("curve mode makes no mesh to save as ") + extension +
                       ": choose a wire or ribbon mode (the curve downloads as curve.svg or result.zip)");
    const fs::path path = scratch / (stem + extension);
    write_mesh(result.mesh, path);
    return StudioDownload{read_and_remove(path), type, base + extension};
  };
  switch (file) {
  case StudioFile::surface:
    return {studio_view_bytes(surface.repaired.mesh, {}), "application/octet-stream", "surface.bin"};
  case StudioFile::view:
    return {curve_mode ? studio_view_bytes({}, result.curve.curves) : studio_view_bytes(result.mesh, {}, result.appearance),
            "application/octet-stream", "view.bin"};
  case StudioFile::texture: {
    if (!textured || result.appearance.materials[0].texture.empty())
      throw UsageError("texture.png: only a duotone result has a texture");
    const Texture& t = result.appearance.materials[0].texture;
    return {io::encode_png(t.rgba.data(), t.width, t.height, 4, "texture.png"), "image/png", base + "_texture.png"};
  }
  case StudioFile::stl: return written_mesh(".stl", "model/stl");
  case StudioFile::threemf: return written_mesh(".3mf", "model/3mf");
  case StudioFile::glb: {
    if (!textured) return written_mesh(".glb", "model/gltf-binary");
    const fs::path path = scratch / (stem + ".glb");
    write_textured_mesh({.mesh = result.mesh, .appearance = result.appearance}, path);
    return {read_and_remove(path), "model/gltf-binary", base + ".glb"};
  }
  case StudioFile::obj_zip: {
    // The writers name the MTL and textures after the OBJ, so each zip gets a folder.
    const fs::path folder = scratch / stem;
    fs::create_directory(folder);
    std::vector<io::ZipEntry> entries;
    try {
      if (curve_mode) {
        write_polylines(result.curve.curves, folder / (base + ".obj"));
      } else {
        Appearance appearance = textured ? result.appearance
                                         : Appearance{.materials = {{.name = "meander", .base_color = {0.72f, 0.45f, 0.2f}}}};
        write_textured_mesh({.mesh = result.mesh, .appearance = std::move(appearance)}, folder / (base + ".obj"));
      }
      std::vector<fs::path> paths(fs::directory_iterator(folder), fs::directory_iterator{});
      std::sort(paths.begin(), paths.end());
      for (const fs::path& path : paths) entries.push_back({path.filename().string(), read_and_remove(path)});
    } catch (...) {
      fs::remove_all(folder);
      throw;
    }
    fs::remove_all(folder);
    return {io::zip_stored(entries), "application/zip", base + ".zip"};
  }
  case StudioFile::svg: {
    const fs::path path = scratch / (stem + ".svg");
    write_polylines(result.curve.curves, path);
    return {read_and_remove(path), "image/svg+xml", base + ".svg"};
  }
  case StudioFile::png: {
    // As `meander curve --png` and `meander wire --png`: the surface hides the back of
    // the curve and of a wire; a ribbon lies in it and is drawn alone.
    Scene scene;
    const StudioMode mode = result.params.mode;
    if (textured) scene.meshes.push_back({.mesh = result.mesh, .appearance = result.appearance});
    else if (!curve_mode) scene.meshes.push_back({.mesh = result.mesh, .color = {0.72f, 0.45f, 0.2f}});
    else scene.curves.push_back({.curves = result.curve.curves});
    if (curve_mode || is_wire(mode))
      scene.meshes.push_back({.mesh = cycle_triangles(result.curve.quads, result.curve.cycle),
                              .color = {0.82f, 0.82f, 0.82f},
                              .style = curve_mode ? MeshStyle::hidden : MeshStyle::faint});
    const fs::path path = scratch / (stem + ".png");
    write_png(render(scene, {.width = 1200, .height = 900, .samples = 4}), path);
    return {read_and_remove(path), "image/png", base + ".png"};
  }
  }
  throw UsageError("unknown result file");
}

StudioSessions::Added StudioSessions::add(StudioSurface surface) {
  std::random_device random;
  std::string id;
  for (int i = 0; i < 4; ++i) {
    char word[9];
    std::snprintf(word, sizeof word, "%08x", unsigned(random()));
    id += word;
  }
  auto session = std::make_shared<Session>();
  session->surface = std::make_shared<const StudioSurface>(std::move(surface));
  std::lock_guard guard(lock_);
  sessions_[id] = {session, ++clock_};
  while (sessions_.size() > capacity_) {
    auto oldest = std::min_element(sessions_.begin(), sessions_.end(),
                                   [](const auto& a, const auto& b) { return a.second.created < b.second.created; });
    sessions_.erase(oldest);
  }
  return {std::move(id), std::move(session)};
}

std::shared_ptr<StudioSessions::Session> StudioSessions::find(std::string_view id) const {
  std::lock_guard guard(lock_);
  const auto it = sessions_.find(std::string(id));
  return it == sessions_.end() ? nullptr : it->second.session;
}

} // namespace meander
