#include "meander/studio.h"

#include "io/binary.h"
#include "io/formats.h"
#include "meander/default_init.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/parameters.h"
#include "meander/remesh.h"
#include "meander/shapes.h"
#include "meander/textured_io.h"
#include "meander/tone_mesh.h"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <optional>
#include <random>

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
  case StudioMode::picture: return "picture";
  }
  return "curve";
}

} // namespace

StudioMode parse_studio_mode(std::string_view name) {
  for (StudioMode mode : {StudioMode::curve, StudioMode::constant_wire, StudioMode::constant_ribbon,
                          StudioMode::variable_wire, StudioMode::variable_ribbon, StudioMode::duotone, StudioMode::picture})
    if (name == mode_name(mode)) return mode;
  throw UsageError("unknown mode '" + std::string(name.substr(0, 40)) +
                   "' (expected curve, constant-wire, constant-ribbon, variable-wire, variable-ribbon, duotone or picture)");
}

namespace {

// The parameter's text from a JSON value: a name as it is, anything else as JSON (so that
// "4" in quotes is not taken for a number).
template <class T> std::string json_text(const json& value) {
  if constexpr (!std::is_arithmetic_v<T>)
    if (value.is_string()) return value.get<std::string>();
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

// Parameters no studio request sets: the mode sets the wire's method and shape, and a
// picture's size was checked when it was uploaded.
bool set_by_the_studio(const Parameter& parameter) {
  return &parameter == &parameters::method || &parameter == &parameters::shape || &parameter == &parameters::max_pixels;
}

// Sets the parameter `key` of the mode's job from `value`; false if no mode's job has it.
// The page sends every mode's parameters: those of other modes are checked, not set, and
// refused only when no job takes the value (a duotone takes no "shaped" tree, a curve does).
bool set_studio_parameter(StudioParams& p, const std::string& key, const json& value) {
  bool known = false, taken = false;
  std::optional<ParameterError> refusal;
  const auto set = [&](auto& job, bool applies) {
    visit_parameters(job, [&](const Parameter& parameter, auto& field) {
      if (parameter.name != key || set_by_the_studio(parameter)) return;
      known = true;
      auto scratch = field;
      try {
        // A length may come as text with its unit ("3mm").
        const std::string text = parameter.length && value.is_string() ? value.get<std::string>()
                                                                       : json_text<std::decay_t<decltype(field)>>(value);
        set_parameter(parameter, text, applies ? field : scratch);
        taken = true;
      } catch (const ParameterError& e) {
        if (applies) throw;
        if (!refusal) refusal = e;
      }
    });
  };
  set(p.wire.curve, p.mode == StudioMode::curve);
  set(p.wire, p.mode != StudioMode::curve && p.mode != StudioMode::duotone && p.mode != StudioMode::picture);
  set(p.duotone, p.mode == StudioMode::duotone);
  set(p.image, p.mode == StudioMode::picture);
  if (!taken && refusal) throw *refusal;
  return known;
}

// Made to a model size: the result's lengths are millimetres.
bool sized(const StudioParams& p) {
  return (p.mode == StudioMode::duotone ? p.duotone.model_size : p.wire.curve.model_size).has_value();
}

// A length with a unit ("3mm") needs the model size: without one, lengths are in the
// model's own units. A picture's lengths are on paper, in millimetres.
void refuse_units_without_model_size(const json& document, const StudioParams& p) {
  if (sized(p) || p.mode == StudioMode::picture) return;
  const auto check = [&](const auto& job) {
    visit_parameters(job, [&](const Parameter& parameter, const auto&) {
      const auto value = document.find(std::string(parameter.name));
      if (value != document.end() && value->is_string())
        check_unit(parameter, value->template get<std::string>(), false, parameters::model_size.name);
    });
  };
  check(p.wire);
  check(p.duotone);
}

} // namespace

MakeRequest parse_make_request(std::string_view body) {
  if (body.size() > max_request_bytes)
    throw UsageError("request body of " + std::to_string(body.size()) + " bytes: a make request is at most " +
                     std::to_string(max_request_bytes));
  const json document = json::parse(body, nullptr, false);
  if (document.is_discarded()) throw UsageError("request body is not valid JSON");
  if (!document.is_object()) throw UsageError("request body: expected a JSON object, got " + describe(document));
  MakeRequest request;
  StudioParams& p = request.params;
  // The mode first: it says which job the other keys set.
  if (const auto mode = document.find("mode"); mode != document.end())
    p.mode = named("mode", [&] { return parse_studio_mode(text(*mode, "mode")); });
  bool has_session = false;
  for (const auto& [key, value] : document.items()) {
    if (key == "session") {
      request.session = text(value, "session");
      has_session = true;
    } else if (key == "preview" || key == "hold") {
      if (!value.is_boolean()) throw UsageError(key + ": expected true or false, got " + describe(value));
      (key == "preview" ? p.preview : request.hold) = value.get<bool>();
    } else if (key != "mode" && !set_studio_parameter(p, key, value)) {
      throw UsageError(describe(json(key)) + ": unknown parameter");
    }
  }
  if (!has_session) throw UsageError("session: missing (upload a mesh first: POST /api/mesh)");
  refuse_units_without_model_size(document, p);
  return request;
}

std::string studio_parameters_json() {
  const auto described = [](const auto& job) {
    json list = json::array();
    visit_parameters(job, [&](const Parameter& p, const auto& value) {
      if (set_by_the_studio(p)) return;
      json entry = {{"name", p.name}, {"help", p.help}, {"default", parameter_text(p, value)}};
      if (std::isfinite(p.min)) entry["min"] = p.min;
      if (std::isfinite(p.max)) entry["max"] = p.max;
      if (!p.choices.empty()) entry["choices"] = std::vector<std::string>(p.choices.begin(), p.choices.end());
      list.push_back(std::move(entry));
    });
    return list;
  };
  const StudioParams defaults;
  return json{{"curve", described(defaults.wire.curve)},
              {"wire", described(defaults.wire)},
              {"duotone", described(defaults.duotone)},
              {"picture", described(defaults.image)}}
      .dump();
}

const std::array<std::string_view, 6> studio_picture_extensions = {".png", ".jpg", ".jpeg", ".bmp", ".tga", ".gif"};

bool is_studio_picture(std::string_view filename) {
  const std::string extension = io::lowercase_extension(std::filesystem::path(filename));
  return std::find(studio_picture_extensions.begin(), studio_picture_extensions.end(), extension) !=
         studio_picture_extensions.end();
}

StudioSurface load_studio_surface(std::string_view filename, std::string_view bytes, int64_t max_faces, int64_t max_pixels) {
  // Only the last component: a client's "../../x.obj" is a name for messages, not a path.
  const size_t slash = filename.find_last_of("/\\");
  std::string name(slash == std::string_view::npos ? filename : filename.substr(slash + 1));
  if (name.empty()) name = "upload";
  if (is_studio_picture(name)) {
    Texture picture = read_texture(bytes, name, max_pixels);
    return {.name = std::move(name), .picture = std::move(picture)};
  }
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
  if (params.mode == StudioMode::picture) {
    // The line's points: at most the room inside the margins in black, with 5 cycle
    // segments a cell (a black picture's line has 4.5), of `samples` points each.
    const ImageJob& job = params.image;
    const Texture& picture = surface.picture;
    double area = std::max(0.0, job.paper.width - 2 * job.paper.margin) * std::max(0.0, job.paper.height - 2 * job.paper.margin);
    if (job.width && picture.width > 0) area = *job.width * (*job.width * picture.height / picture.width);
    return int64_t(std::min(black_tone_cells(area, job.tone), 1e12)) * 5 * job.curve.samples;
  }
  const PolygonMesh& mesh = surface.repaired.mesh;
  int64_t faces = mesh.num_faces(), corners = int64_t(mesh.face_vertices.size()), edges = surface.repaired.connectivity.num_edges();
  const bool duotone = params.mode == StudioMode::duotone;
  const std::optional<double> spacing = duotone ? params.duotone.spacing : params.wire.curve.spacing;
  if (spacing) {
    // The remeshed surface's triangles, from its area (remeshed_faces_estimate), bounded
    // so that the products below cannot overflow.
    const Quadrangulation q = duotone ? params.duotone.duotone.quadrangulation : params.wire.curve.quadrangulation;
    const std::optional<double> size = duotone ? params.duotone.model_size : params.wire.curve.model_size;
    faces = std::min<int64_t>(remeshed_faces(mesh, size, spacing, q), int64_t(1) << 40);
    corners = 3 * faces;
    edges = corners / 2 + 1;
  }
  // Quads per quadrangulation (quadrangulate.h): one per edge, one per corner, the faces.
  const auto quads = [&](Quadrangulation q) {
    switch (q) {
    case Quadrangulation::dual_simplest: return edges > 0 ? edges : corners;
    case Quadrangulation::catmull_clark: return corners;
    case Quadrangulation::none: return faces;
    }
    return corners;
  };
  if (params.mode == StudioMode::duotone) {
    const TileOptions& tiles = params.duotone.tiles;
    const int64_t texture = int64_t(tiles.texture_size) * tiles.texture_size / 2; // the atlas
    // A shell's two solids: a quad's tiles outside and inside, and the walls along its
    // cut (arcs: 136 triangles a quad for the two, measured on either quadrangulation).
    const int64_t shell = params.duotone.shell && !params.preview ? 160 : 0;
    const int64_t q = quads(params.duotone.duotone.quadrangulation);
    return 4 * q * (int64_t(1) << (2 * params.duotone.subdivide)) + shell * q + texture;
  }
  const WireJob& wire = params.wire;
  int64_t cycle = 2 * quads(wire.curve.quadrangulation); // triangles the cycle visits
  if (params.mode == StudioMode::curve) return cycle * wire.curve.curve.samples;
  if (wire_curve_job(wire).slab_mesh && !spacing) { // a remeshed surface has no polygons to split
    // The slab mesh splits a polygon of n >= 5 sides into a star: n more edges (dual of
    // Simplest's quads), 2n more corners (Catmull-Clark's).
    const int star_sides = SlabMeshOptions{}.star_sides;
    const int64_t per_side = wire.curve.quadrangulation == Quadrangulation::catmull_clark ? 4 : 2;
    for (int32_t f = 0; f < mesh.num_faces(); ++f)
      if (mesh.face_size(f) >= star_sides) cycle += per_side * mesh.face_size(f);
  }
  return wire_triangles(cycle, wire);
}

// The job that makes the curve of a curve or wire mode.
CurveJob studio_curve_job(const StudioParams& params) {
  CurveJob job = params.mode == StudioMode::curve ? params.wire.curve : wire_curve_job(params.wire);
  job.cycle.count_leaves = true;
  return job;
}

// What is made: the wire's method and shape the mode's, and a preview's reductions
// (StudioParams::preview).
StudioParams effective(const StudioSurface& surface, StudioParams params) {
  const StudioMode mode = params.mode;
  params.wire.method = mode == StudioMode::variable_wire || mode == StudioMode::variable_ribbon ? WireMethod::variable : WireMethod::constant;
  params.wire.shape = mode == StudioMode::constant_ribbon || mode == StudioMode::variable_ribbon ? WireShape::ribbon : WireShape::wire;
  // The page sends every mode's settings; bridges are the wires' (not the ribbons'), and
  // a preview shows the wire without them (their union costs several times the wire).
  if ((mode != StudioMode::constant_wire && mode != StudioMode::variable_wire) || params.preview) params.wire.bridges.reset();
  if (!params.preview) return params;
  params.duotone.shell.reset(); // the two-colour print is the full result's
  params.duotone.min_thickness = params.duotone.clearance = 0;
  params.image.curve.samples = std::min(params.image.curve.samples, 2);
  int& samples = params.wire.curve.curve.samples;
  samples = std::min(samples, 2);
  // Two rounds of relaxation show how even the full result will be (it relaxes all) on a
  // small surface: a round costs about 1.4 us a point on two cores, 3.4 points a remeshed
  // face, so 0.1 s at studio_preview_relax_faces. A larger one shows the curve as made
  // on the even surface, moved onto the input.
  CurveJob& curve = params.wire.curve;
  const bool small = remeshed_faces(surface.repaired.mesh, curve.model_size, curve.spacing, curve.quadrangulation) <=
                     studio_preview_relax_faces;
  curve.relax = small ? std::min(curve.relax, 2) : 0;
  params.wire.levels = 0;
  params.wire.report = false;
  params.wire.clear = false; // the search for self-intersections costs more than the wire
  params.duotone.subdivide = 0;
  while (samples > 1 && result_size(surface, params) > studio_preview_budget) --samples;
  // A wire of 8 sides, or of slabs, has 4 to 8 times the triangles of its ribbon.
  if ((mode == StudioMode::constant_wire || mode == StudioMode::variable_wire) && result_size(surface, params) > studio_preview_budget)
    params.wire.shape = WireShape::ribbon;
  // A variable ribbon still over it has a rung a triangle, not two: half the triangles,
  // and on so many of them each is a few pixels, where the connectors do not show.
  if (params.wire.method == WireMethod::variable && result_size(surface, params) > studio_preview_budget) params.wire.rungs = 1;
  return params;
}

} // namespace

int64_t studio_result_size(const StudioSurface& surface, const StudioParams& requested) {
  return result_size(surface, effective(surface, requested));
}

StudioResult make_studio_result(const StudioSurface& surface, const StudioParams& requested, const StudioResult* previous,
                                Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  const StudioParams params = effective(surface, requested);
  StudioResult result{.params = params};
  const StudioMode mode = params.mode;
  const RepairResult& input = surface.repaired;
  const bool picture = !surface.picture.empty();
  if (picture != (mode == StudioMode::picture))
    throw UsageError(surface.name + (picture ? ": a picture: only picture mode draws it (open a mesh for the other modes)"
                                             : ": a mesh: picture mode draws a picture (open a .png or .jpg)"));
  // The library's refusals do not know the upload's name; the user should still read it.
  const auto about_surface = [&](auto&& work) {
    try {
      return work();
    } catch (const TopologyError& e) {
      throw TopologyError(surface.name + ": " + e.what());
    } catch (const InputError& e) {
      throw InputError(surface.name + ": " + e.what());
    }
  };
  if (mode == StudioMode::picture) {
    ImageJob job = params.image;
    job.cycle.count_leaves = true;
    result.picture = about_surface([&] { return make_line_picture(surface.picture, job, nullptr, progress); });
    result.curve.curves = result.picture.curve;
    result.curve.cycle.leaves = result.picture.leaves;
    result.curve_length = result.picture.drawing.drawn_length;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
  // The even surface of a spacing: the result before's when made for the same one (a
  // slider other than the spacing, model size or quad is moving).
  const auto even_surface = [&](const EvenSurfaceOptions& options) {
    if (previous && previous->even && previous->even->options == options) return previous->even;
    if (progress) progress->begin("remesh");
    return std::make_shared<const EvenSurface>(about_surface([&] { return make_even_surface(input.mesh, options); }));
  };
  if (mode == StudioMode::duotone) {
    const DuotoneJob& job = params.duotone;
    if (job.spacing) result.even = even_surface(even_surface_options(job));
    Duotone duotone = about_surface([&] {
      return result.even ? make_duotone(*result.even, job, progress) : make_duotone(input.mesh, input.connectivity, job, progress);
    });
    const bool same_atlas = previous && previous->params.mode == StudioMode::duotone &&
                            previous->params.duotone.tiles == job.tiles && !previous->appearance.materials.empty();
    TexturedMesh painted =
        paint_duotone(duotone, job, same_atlas ? previous->appearance.materials[0].texture : Texture{}, nullptr, progress);
    if (job.shell) {
      if (progress) progress->begin("shell");
      // Where the surface cannot be thickened, or not with this wall or gap, the painted
      // duotone is still shown, and the stats say why there is no print.
      try {
        result.shell = make_shell(duotone, job);
      } catch (const TopologyError& e) {
        result.shell_refusal = e.what();
      } catch (const ParameterError& e) {
        result.shell_refusal = e.what();
      }
    }
    if (progress) progress->begin("separating curves");
    result.curve.curves = separating_curves(duotone, job.tiles.style);
    result.curve_length = total_length(result.curve.curves);
    result.curve.quads = std::move(duotone.quads);
    result.curve.cycle = std::move(duotone.cycle);
    result.mesh = std::move(painted.mesh);
    result.appearance = std::move(painted.appearance);
    for (int32_t f = 0; f < result.mesh.num_faces(); ++f) result.triangles += std::max(0, result.mesh.face_size(f) - 2);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
  WireJob job = params.wire;
  job.measure_thickness = false; // the live view's stats: rays cost more than the wire
  // The curve is the result before's when the same job made it (a wire's own slider is
  // moving: s, t, thickness, sides, radius): the same curve, without its time.
  const CurveJob curve_job = studio_curve_job(params);
  if (curve_job.spacing) result.even = even_surface(even_surface_options(curve_job));
  if (previous && previous->params.mode != StudioMode::duotone && studio_curve_job(previous->params) == curve_job)
    result.curve = previous->curve;
  else
    result.curve = about_surface([&] {
      return result.even ? make_curve(*result.even, curve_job, nullptr, progress)
                         : make_curve(input.mesh, input.connectivity, curve_job, nullptr, progress);
    });
  result.curve_length = total_length(result.curve.curves);
  // How even a curve of a chosen spacing came out, for the stats beside it.
  if (job.curve.spacing && !params.preview && result.curve.surface.num_faces() > 0) {
    if (progress) progress->begin("evenness");
    result.evenness = measure_evenness(result.curve.surface, result.curve.curves, {.surface_samples = 10000});
  }
  if (mode == StudioMode::curve) {
    result.triangles = int64_t(result.curve.cycle.order.size());
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
  if (job.method == WireMethod::constant && !job.radius && params.preview) {
    // The check that grows the analytic bound costs more than the wire, so a preview
    // does without it: it takes the radius of the full result before it when that was
    // made on the same curve (another slider is moving), so that the preview is as
    // thick as the result that follows; else the bound on its own, coarser curve.
    StudioParams full = requested;
    full.preview = false;
    const StudioParams* before = previous ? &previous->params : nullptr;
    const bool same_curve = before && !before->preview && before->mode == mode && !before->wire.radius && previous->radius > 0 &&
                            studio_curve_job(*before) == studio_curve_job(effective(surface, full));
    if (progress) progress->begin("radius");
    const double radius = same_curve ? previous->radius
                                     : max_wire_radius(result.curve.curves,
                                                       job.curve.curve.smoothing == Smoothing::none ? 1 : job.curve.curve.samples);
    if (!(radius > 0))
      throw TopologyError(surface.name + ": the curve touches itself: no wire radius avoids a self-intersection");
    job.radius = radius;
  }
  WireResult made = about_surface([&] { return make_wire(result.curve, job, nullptr, progress); });
  result.mesh = std::move(made.mesh);
  result.radius = made.radius;
  result.bridges = std::move(made.bridges);
  result.bridge_faces = std::move(made.bridge_faces);
  result.report = made.report;
  result.surface_crossings = int32_t(made.surface_crossings.size());
  if (params.preview)
    for (int32_t f = 0; f < result.mesh.num_faces(); ++f) result.triangles += std::max(0, result.mesh.face_size(f) - 2);
  else
    result.triangles = result.report.triangles;
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
  if (result.params.mode != StudioMode::picture) stats["millimetres"] = sized(result.params);
  if (result.curve.cycle.leaves >= 0) stats["leaves"] = result.curve.cycle.leaves;
  if (result.evenness) {
    stats["gap_median"] = result.evenness->gap_median;
    stats["gap_cv"] = result.evenness->gap_cv;
  }
  if (result.params.mode == StudioMode::picture) {
    const Drawing& drawing = result.picture.drawing;
    stats["cells"] = result.picture.cells;
    stats["paper"] = {drawing.paper.width, drawing.paper.height};
    stats["pen_up_travel"] = drawing.travel;
  } else if (result.params.mode == StudioMode::duotone) {
    stats["quads"] = result.curve.quads.num_quads();
    stats["faces"] = result.mesh.num_faces();
    // What the atlas depends on: the page fetches texture.png again only when it changes.
    const TileOptions& tiles = result.params.duotone.tiles;
    std::string texture(to_string(tiles.style));
    for (const Color8& c : tiles.colors) {
      char hex[9];
      std::snprintf(hex, sizeof hex, " #%02x%02x%02x", c[0], c[1], c[2]);
      texture += hex;
    }
    stats["texture"] = texture + " " + std::to_string(tiles.texture_size);
    if (result.shell) {
      stats["shell"] = {{"volumes", result.shell->volumes},
                        {"below_floor_corners", result.shell->below_floor_corners},
                        {"summary", shell_summary(*result.shell, result.params.duotone)}};
      if (result.params.duotone.clearance > 0) stats["shell"]["apart"] = result.shell->apart;
    } else if (!result.shell_refusal.empty()) {
      stats["shell"] = {{"refused", result.shell_refusal}};
    }
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
    // A wire's preview over its budget is drawn as the wire's ribbon (its footprint).
    if (result.params.wire.shape == WireShape::ribbon &&
        (result.params.mode == StudioMode::constant_wire || result.params.mode == StudioMode::variable_wire))
      stats["preview_as_ribbon"] = true;
    if (result.params.wire.rungs == 1) stats["preview_rungs"] = 1;
    stats["stars"] = result.curve.stars;
    stats["cap_flips"] = result.curve.cap_flips;
    stats["cap_cuts"] = result.curve.cap_cuts;
    stats["needle_collapses"] = result.curve.needle_collapses;
    if (result.radius > 0) stats["radius"] = result.radius;
    else stats["radius"] = nullptr;
    if (result.params.wire.bridges)
      stats["bridges"] = {{"count", result.bridges.ends.size()},
                          {"longest_stretch", result.bridges.longest_stretch},
                          {"every_pass_tied", result.bridges.every_pass_tied}};
  }
  return stats.dump();
}

StudioFile parse_studio_file(std::string_view name) {
  static constexpr std::pair<std::string_view, StudioFile> table[] = {
      {"surface.bin", StudioFile::surface}, {"view.bin", StudioFile::view},      {"texture.png", StudioFile::texture},
      {"result.stl", StudioFile::stl},
      {"result.3mf", StudioFile::threemf},  {"result.glb", StudioFile::glb},     {"result.zip", StudioFile::obj_zip},
      {"curve.svg", StudioFile::svg},       {"render.png", StudioFile::png},     {"duotone.svg", StudioFile::duotone_svg},
      {"print.3mf", StudioFile::print}};
  for (const auto& [file_name, file] : table)
    if (name == file_name) return file;
  throw UsageError("no result file of that name (expected surface.bin, view.bin, texture.png, result.stl, result.3mf, "
                   "result.glb, result.zip, curve.svg, render.png, duotone.svg or print.3mf)");
}

std::string studio_view_bytes(const PolygonMesh& mesh, const Polylines& curves, const Appearance& appearance) {
  const bool textured = !appearance.texcoords.empty();
  int64_t triangles = 0, segments = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) triangles += std::max(0, mesh.face_size(f) - 2);
  for (size_t k = 0; k + 1 < curves.start.size(); ++k) {
    const int32_t n = curves.start[k + 1] - curves.start[k];
    const bool open = !curves.open.empty() && curves.open[k];
    segments += n < 2 ? 0 : (open ? n - 1 : n);
  }
  const bool shaded = triangles > 0;
  if (int64_t(mesh.face_vertices.size()) + int64_t(curves.points.size()) > UINT32_MAX / 2 || 3 * triangles > UINT32_MAX / 2 ||
      2 * segments > UINT32_MAX / 2)
    throw UsageError("result too large for the view (over 2^31 elements)");

  // The mesh's view vertices: its vertices, or with texture coordinates each distinct
  // (vertex, texture coordinate) pair of its corners, as texture seams need (a duotone's
  // corners share about a third of them). `source` is a view vertex's first corner, or
  // its vertex; `corner_of` a corner's view vertex.
  std::vector<uint32_t> corner_of, source;
  if (textured) {
    const size_t n = mesh.positions.size();
    std::vector<uint32_t> first(n + 1, 0), corners(mesh.face_vertices.size());
    for (const int32_t v : mesh.face_vertices) ++first[size_t(v) + 1];
    for (size_t v = 0; v < n; ++v) first[v + 1] += first[v];
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (size_t c = 0; c < mesh.face_vertices.size(); ++c) corners[fill[size_t(mesh.face_vertices[c])]++] = uint32_t(c);
    corner_of.resize(mesh.face_vertices.size());
    for (size_t v = 0; v < n; ++v) {
      const size_t distinct = source.size();
      for (uint32_t i = first[v]; i < first[v + 1]; ++i) {
        const uint32_t c = corners[i];
        size_t k = distinct;
        while (k < source.size() && !(appearance.texcoords[source[k]] == appearance.texcoords[c])) ++k;
        if (k == source.size()) source.push_back(c);
        corner_of[c] = uint32_t(k);
      }
    }
  } else {
    source.resize(mesh.positions.size());
    std::iota(source.begin(), source.end(), 0u);
  }
  std::vector<uint32_t> indices;
  indices.reserve(size_t(3 * triangles));
  // Polygons fanned: corners (start, start + i, start + i + 1); a quad as 0-1-2, 0-2-3.
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    for (int32_t i = 1; i + 1 < mesh.face_size(f); ++i)
      for (const int32_t c : {0, i, i + 1}) {
        const size_t corner = size_t(mesh.face_start[f] + c);
        indices.push_back(textured ? corner_of[corner] : uint32_t(mesh.face_vertices[corner]));
      }
  // Numbered in the order the triangles first use them (vertices no face uses left out),
  // which halves what the index codec makes of a ribbon's strips.
  std::vector<uint32_t> order(source.size());
  const size_t mesh_vertices =
      meshopt_optimizeVertexFetchRemap(order.data(), indices.data(), indices.size(), source.size());
  for (uint32_t& i : indices) i = order[i];
  std::vector<uint32_t> sources(mesh_vertices); // the view's mesh vertices' sources, in order
  for (size_t k = 0; k < source.size(); ++k)
    if (order[k] != ~0u) sources[order[k]] = source[k];
  auto vertex_of = [&](uint32_t s) { return size_t(textured ? mesh.face_vertices[s] : int32_t(s)); };
  const size_t v = mesh_vertices + curves.points.size();

  std::string out(48, '\0');
  char* at = out.data();
  auto put = [&at](auto value) {
    io::store_little_endian(at, value);
    at += sizeof(value);
  };
  std::memcpy(at, "MND3", 4);
  at += 4;
  put(uint32_t(v));
  put(uint32_t(triangles));
  put(uint32_t(segments));
  put(uint32_t((textured ? 1 : 0) | (shaded ? 2 : 0)));
  put(uint32_t(0));
  Box3 box = bounding_box(mesh.positions);
  for (const Vec3& p : curves.points) box.extend(p);
  for (const float x : {box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z}) put(x);
  // Each array compressed by meshoptimizer's codecs (the page decodes them with its
  // WebAssembly decoder, which three.js ships): the browser took a view's bytes at about
  // 50 MB/s here, most of a preview's time. The arrays are made side by side (each codec
  // is sequential), then written in order: each as its byte count, then the bytes,
  // padded to 4.
  using Bytes = UninitVector<unsigned char>; // the codecs' bounds are generous: not zeroed
  auto encode_vertices = [v](const void* data, size_t size) {
    Bytes encoded(meshopt_encodeVertexBufferBound(v, size));
    encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, v, size));
    return encoded;
  };
  Bytes positions, normals, texcoords, faces, lines;
  tbb::parallel_invoke(
      [&] {
        // Positions as 16-bit steps of the box's largest side from its low corner (a
        // 65,535th of it: finer than a pixel of any view), which the vertex codec packs to
        // a third of float32's bytes; a 4th zero, as for the normals.
        const double scale = 65535 / std::max(double(box.largest_side()), 1e-30);
        std::vector<std::array<uint16_t, 4>> quantized;
        quantized.reserve(v);
        auto quantize = [&](Vec3 p) { // rounded, without a libm call per coordinate
          const double x[3] = {double(p.x) - box.min.x, double(p.y) - box.min.y, double(p.z) - box.min.z};
          std::array<uint16_t, 4> q{};
          for (int k = 0; k < 3; ++k) q[size_t(k)] = uint16_t(std::min(x[k] * scale + 0.5, 65535.0));
          quantized.push_back(q);
        };
        for (const uint32_t s : sources) quantize(mesh.positions[vertex_of(s)]);
        for (const Vec3& p : curves.points) quantize(p);
        positions = encode_vertices(quantized.data(), sizeof(quantized[0]));
      },
      [&] {
        if (shaded) {
          // The normals are computed here, not in the page: a JavaScript loop over millions
          // of triangles took longer than making a preview. A 4th byte of zero: the vertex
          // codec takes elements of a multiple of 4 bytes.
          const std::vector<Vec3> vertex_normal = vertex_normals(mesh);
          std::vector<std::array<int8_t, 4>> packed(v, {0, 0, 0, 0});
          auto pack = [](Vec3 n) { // rounded half away from zero, without a libm call per component
            std::array<int8_t, 4> q{};
            const float x[3] = {n.x, n.y, n.z};
            for (int k = 0; k < 3; ++k) q[size_t(k)] = int8_t(x[k] * 127.0f + (x[k] < 0 ? -0.5f : 0.5f));
            return q;
          };
          for (size_t i = 0; i < mesh_vertices; ++i) packed[i] = pack(vertex_normal[vertex_of(sources[i])]);
          normals = encode_vertices(packed.data(), 4); // the curve's points have no normal: zero
        }
        if (textured) {
          // As 16-bit fractions of the atlas (an eighth of a texel of the largest, 8192
          // wide), which the vertex codec packs smaller than float32.
          std::vector<std::array<uint16_t, 2>> uv(v, {0, 0}); // the curve's points: (0, 0)
          auto fraction = [](float x) { return uint16_t(std::clamp(x, 0.0f, 1.0f) * 65535.0f + 0.5f); };
          for (size_t i = 0; i < mesh_vertices; ++i) {
            const TexCoord& t = appearance.texcoords[sources[i]];
            uv[i] = {fraction(t.u), fraction(t.v)};
          }
          texcoords = encode_vertices(uv.data(), sizeof(uv[0]));
        }
      },
      [&] {
        if (triangles > 0) {
          faces.resize(meshopt_encodeIndexBufferBound(indices.size(), v));
          faces.resize(meshopt_encodeIndexBuffer(faces.data(), faces.size(), indices.data(), indices.size()));
        }
        if (segments > 0) {
          std::vector<uint32_t> ends;
          ends.reserve(size_t(2 * segments));
          const uint32_t base = uint32_t(mesh_vertices);
          for (size_t k = 0; k + 1 < curves.start.size(); ++k) {
            const int32_t begin = curves.start[k], end = curves.start[k + 1];
            if (end - begin < 2) continue;
            for (int32_t i = begin; i + 1 < end; ++i) ends.insert(ends.end(), {base + uint32_t(i), base + uint32_t(i + 1)});
            if (curves.open.empty() || !curves.open[k]) ends.insert(ends.end(), {base + uint32_t(end - 1), base + uint32_t(begin)});
          }
          lines.resize(meshopt_encodeIndexSequenceBound(ends.size(), v));
          lines.resize(meshopt_encodeIndexSequence(lines.data(), lines.size(), ends.data(), ends.size()));
        }
      });
  auto append = [&out](const Bytes& bytes) {
    char length[4];
    io::store_little_endian(length, uint32_t(bytes.size()));
    out.append(length, 4);
    out.append(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    out.append((4 - bytes.size() % 4) % 4, '\0');
  };
  size_t size = out.size();
  for (const Bytes* bytes : {&positions, &normals, &texcoords, &faces, &lines}) size += 4 + (bytes->size() + 3) / 4 * 4;
  out.reserve(size);
  append(positions);
  if (shaded) append(normals);
  if (textured) append(texcoords);
  if (triangles > 0) append(faces);
  if (segments > 0) append(lines);
  return out;
}

StudioPicture parse_studio_picture(const std::multimap<std::string, std::string>& query) {
  StudioPicture picture;
  std::optional<Vec3d> eye, target;
  CameraPose camera;
  for (const auto& [key, value] : query) {
    const auto vector = [&] {
      Vec3d v;
      char more = 0;
      if (std::sscanf(value.c_str(), "%lf,%lf,%lf%c", &v.x, &v.y, &v.z, &more) != 3 || !std::isfinite(norm(v)))
        throw UsageError(key + ": expected three numbers X,Y,Z, got '" + value.substr(0, 60) + "'");
      return v;
    };
    if (key == "size") {
      parse_size(value, picture.width, picture.height);
    } else if (key == "eye") {
      eye = vector();
    } else if (key == "target") {
      target = vector();
    } else if (key == "up") {
      camera.up = vector();
    } else if (key == "fov") {
      char* end = nullptr;
      camera.fov_degrees = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !(camera.fov_degrees > 0 && camera.fov_degrees < 180))
        throw UsageError("fov: expected degrees between 0 and 180, got '" + value.substr(0, 60) + "'");
    } else {
      throw UsageError("'" + key.substr(0, 40) + "': unknown picture option (expected size, eye, target, up or fov)");
    }
  }
  if (eye.has_value() != target.has_value()) throw UsageError("eye and target: give both, or neither");
  if (eye) {
    camera.eye = *eye;
    camera.target = *target;
    picture.camera = camera;
  }
  return picture;
}

StudioDownload studio_download(const StudioSurface& surface, const StudioResult& result, StudioFile file,
                               const StudioPicture& picture) {
  // A preview's files say so in their names, so that a script's saved files tell it too.
  const std::string base = sanitized(fs::path(surface.name).stem().string()) + "_" + mode_name(result.params.mode) +
                           (result.params.preview ? "_preview" : "");
  const bool curve_mode = result.params.mode == StudioMode::curve;
  const bool picture_mode = result.params.mode == StudioMode::picture;
  const bool textured = !result.appearance.materials.empty();
  const bool millimetres = sized(result.params);
  auto mesh_file = [&](const char* extension, const char* type) {
    if (picture_mode)
      throw UsageError(std::string("picture mode makes no mesh to save as ") + extension +
                       ": its line downloads as curve.svg or result.zip");
    if (curve_mode)
      throw UsageError(std::string("curve mode makes no mesh to save as ") + extension +
                       ": choose a wire or ribbon mode (the curve downloads as curve.svg or result.zip)");
    return StudioDownload{mesh_file_bytes(result.mesh, base + extension, {.millimetres = millimetres}), type, base + extension};
  };
  switch (file) {
  case StudioFile::surface:
    if (!surface.picture.empty()) throw UsageError("surface.bin: a picture has no surface (its drawing is curve.svg)");
    return {studio_view_bytes(surface.repaired.mesh, {}), "application/octet-stream", "surface.bin"};
  case StudioFile::view:
    return {curve_mode || picture_mode ? studio_view_bytes({}, result.curve.curves)
                                       : studio_view_bytes(result.mesh, {}, result.appearance),
            "application/octet-stream", "view.bin"};
  case StudioFile::texture: {
    if (!textured || result.appearance.materials[0].texture.empty())
      throw UsageError("texture.png: only a duotone result has a texture");
    const Texture& t = result.appearance.materials[0].texture;
    return {png_file_bytes({.width = t.width, .height = t.height, .has_alpha = true, .rgba = t.rgba}), "image/png",
            base + "_texture.png"};
  }
  case StudioFile::stl: return mesh_file(".stl", "model/stl");
  case StudioFile::threemf: return mesh_file(".3mf", "model/3mf");
  case StudioFile::glb: {
    if (!textured) return mesh_file(".glb", "model/gltf-binary");
    const std::vector<NamedFile> glb =
        textured_mesh_files({.mesh = result.mesh, .appearance = result.appearance}, base + ".glb", millimetres);
    return {glb.front().bytes, "model/gltf-binary", base + ".glb"};
  }
  case StudioFile::obj_zip: {
    std::vector<NamedFile> files;
    if (picture_mode) {
      files.push_back({base + ".obj", polylines_file_bytes(line_picture_curve(result.picture), base + ".obj")});
    } else if (curve_mode) {
      files.push_back({base + ".obj", polylines_file_bytes(result.curve.curves, base + ".obj")});
    } else {
      Appearance appearance = textured ? result.appearance
                                       : Appearance{.materials = {{.name = "meander", .base_color = {0.72f, 0.45f, 0.2f}}}};
      files = textured_mesh_files({.mesh = result.mesh, .appearance = std::move(appearance)}, base + ".obj");
    }
    std::sort(files.begin(), files.end(), [](const NamedFile& a, const NamedFile& b) { return a.name < b.name; });
    return {zip_archive(files), "application/zip", base + ".zip"};
  }
  case StudioFile::svg: {
    if (picture_mode) return {drawing_svg(result.picture.drawing, result.params.image.pen), "image/svg+xml", base + ".svg"};
    // A duotone's separating curves are hidden by its painted surface, the others by the
    // surface their curve lies on. With the page's camera, the plotter drawing of the view
    // on an A4 sheet turned as the view is; without, what `meander curve -o .svg` writes.
    const bool duotone = result.params.mode == StudioMode::duotone;
    if (!picture.camera)
      return {duotone ? curve_svg(result.curve.curves, result.mesh, millimetres) : curve_svg(result.curve, millimetres),
              "image/svg+xml", base + ".svg"};
    const DrawingOptions options{.camera = picture.camera, .paper = parse_paper("A4", picture.width > picture.height)};
    const Drawing drawing = duotone ? draw_curves(result.curve.curves, result.mesh, options) : draw_curve(result.curve, options);
    return {drawing_svg(drawing, options.pen), "image/svg+xml", base + ".svg"};
  }
  case StudioFile::png: {
    if (picture_mode)
      return {png_file_bytes(drawing_image(result.picture.drawing, result.params.image.pen, picture.width, picture.height)),
              "image/png", base + ".png"};
    // As `meander curve --png`, `meander wire --png` and `meander duotone --png` draw it.
    const Scene scene = textured   ? duotone_scene({.mesh = result.mesh, .appearance = result.appearance})
                        : curve_mode ? curve_scene(result.curve)
                                     : wire_scene(result.mesh, result.curve, result.params.wire, MeshStyle::faint,
                                                  result.bridge_faces);
    return {png_file_bytes(
                render(scene, {.width = picture.width, .height = picture.height, .samples = 4, .camera = picture.camera})),
            "image/png", base + ".png"};
  }
  case StudioFile::print: {
    if (!result.shell)
      throw UsageError(result.shell_refusal.empty()
                           ? "print.3mf: only a duotone made with a shell (its wall's thickness) is a two-colour print"
                           : "print.3mf: no two-colour print of this duotone: " + result.shell_refusal);
    const std::array<ColoredPart, 2> parts =
        colored_parts(result.shell->solids[0], result.shell->solids[1], result.params.duotone.tiles.colors);
    return {parts_3mf_bytes(parts, base + "_print.3mf"), "model/3mf", base + "_print.3mf"};
  }
  case StudioFile::duotone_svg:
    if (!picture_mode) throw UsageError("duotone.svg: only a picture's line bounds a duotone drawn on paper");
    return {line_picture_duotone_svg(result.picture, result.params.image), "image/svg+xml", base + "_duotone.svg"};
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

std::shared_ptr<Progress> StudioSessions::Session::start_job(std::function<bool()> abandoned) {
  auto job = std::make_shared<Progress>(std::move(abandoned));
  std::lock_guard guard(job_lock_);
  if (job_) job_->cancel();
  job_ = job;
  return job;
}

void StudioSessions::Session::end_job(const std::shared_ptr<Progress>& job) {
  std::lock_guard guard(job_lock_);
  if (job_ == job) job_.reset();
}

bool StudioSessions::Session::cancel_job() {
  std::lock_guard guard(job_lock_);
  if (!job_) return false;
  job_->cancel();
  return true;
}

std::optional<Progress::State> StudioSessions::Session::job_state() const {
  std::lock_guard guard(job_lock_);
  if (!job_) return std::nullopt;
  return job_->state();
}

std::shared_ptr<StudioSessions::Session> StudioSessions::find(std::string_view id) const {
  std::lock_guard guard(lock_);
  const auto it = sessions_.find(std::string(id));
  return it == sessions_.end() ? nullptr : it->second.session;
}

} // namespace meander
