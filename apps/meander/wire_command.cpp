#include "cli_support.h"
#include "commands.h"
#include "picture_options.h"

#include "meander/error.h"
#include "meander/io.h"
#include "meander/pipeline.h"
#include "meander/printability.h"
#include "meander/render.h"
#include "meander/wire.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace meander::cli {

namespace {

struct WireArgs {
  std::string input, output, report, png;
  std::string method = "constant", shape = "wire", radius = "auto";
  CurveFlags curve;
  PictureArgs picture;
  int sides = 8, levels = 2;
  double s = 0.6, t = 0.6, thickness = 0, cap_angle = 120, min_thickness = 0;
  bool keep_faces = false;
  bool strict = false, verbose = false;
};

// "auto" (none) or a positive number.
std::optional<double> parse_radius(const std::string& text) {
  if (text == "auto") return std::nullopt;
  double r = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), r);
  if (ec != std::errc() || end != text.data() + text.size() || !(r > 0) || !std::isfinite(r))
    throw UsageError("--radius '" + text + "': expected a positive number or auto");
  return r;
}

// Making and checking a wire takes 110 (constant wire) to 234 (variable ribbon) bytes
// per triangle at its peak, measured on the 100k-face sphere (docs/benchmarks.md).
constexpr double kBytesPerTriangle = 240;

// Refuses a wire that would not fit in memory, naming the largest --levels that fits or
// the options to lower.
void require_memory_for(const WireArgs& a, const VariableWireOptions& variable, int64_t triangles, int64_t cycle_triangles) {
  const auto what = [&] { return "the " + a.method + " " + a.shape + " would have " + std::to_string(triangles) + " triangles"; };
  const auto advice = [&](double memory) -> std::string {
    if (a.method != "variable")
      return "lower --samples (" + std::to_string(a.curve.samples) + ")" +
             (a.shape == "wire" ? " or --sides (" + std::to_string(a.sides) + ")" : std::string()) + ", or use a coarser mesh";
    VariableWireOptions lower = variable;
    while (--lower.levels >= 0)
      if (double(variable_wire_triangles(cycle_triangles, lower)) * kBytesPerTriangle <= memory)
        return "use --levels " + std::to_string(lower.levels) + " or a coarser mesh";
    return "use a coarser mesh";
  };
  require_memory(a.input, double(triangles), kBytesPerTriangle, what, advice);
}

void run_wire(const WireArgs& a) {
  const bool constant = a.method == "constant";
  CurveJob job = curve_job(a.curve);
  if (!constant && !a.keep_faces) {
    job.slab_mesh = SlabMeshOptions{};
    if (a.cap_angle < 180) job.slab_mesh->caps->cap_angle_degrees = a.cap_angle;
    else job.slab_mesh->caps.reset();
  }
  const WireShape shape = parse_wire_shape(a.shape);
  if (shape == WireShape::ribbon && a.min_thickness > 0)
    throw UsageError("--min-thickness applies to wires: a ribbon is a band with no thickness to measure");
  const std::optional<double> radius = parse_radius(a.radius);
  const VariableWireOptions variable{.shape = shape, .s = a.s, .t = a.t, .thickness = a.thickness, .levels = a.levels};
  const ConstantWireOptions constant_options{.shape = shape, .radius = radius, .sides = a.sides, .curve = job.curve};
  require_output_path(a.output, {".stl", ".ply", ".obj", ".off", ".glb", ".3mf"}, "-o");
  if (!a.report.empty()) require_output_path(a.report, {".json"}, "--report");
  if (!a.png.empty()) require_output_path(a.png, {".png"}, "--png");
  const RenderOptions picture = picture_options(a.picture);

  StageLog log(a.verbose);
  RepairResult input = read_and_repair(a.input, log, {.strict = a.strict, .max_faces = a.curve.max_faces, .reorder = reorders(job)});
  StageTimes times;
  const CurveResult curve =
      about_input(a.input, [&] { return make_curve(std::move(input.mesh), std::move(input.connectivity), job, &times); });
  for (const auto& [stage, seconds] : times) log.add(stage, seconds);
  log.restart();
  if (curve.stars + curve.cap_flips + curve.cap_cuts + curve.needle_collapses > 0) {
    const auto count = [](int64_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
    std::vector<std::string> done;
    if (curve.stars > 0)
      done.push_back("split " + count(curve.stars, "polygon", "polygons") + " of " + std::to_string(job.slab_mesh->star_sides) +
                     " or more sides into triangles around " + (curve.stars == 1 ? "its centre" : "their centres"));
    char angle[32];
    std::snprintf(angle, sizeof angle, "%g", a.cap_angle);
    if (curve.cap_flips > 0) done.push_back("flipped " + count(curve.cap_flips, "edge", "edges") + " facing an angle over " + angle + " degrees");
    if (curve.cap_cuts > 0)
      done.push_back("cut off " + count(curve.cap_cuts, "triangle", "triangles") + " with an angle over " + angle + " degrees on the boundary");
    if (curve.needle_collapses > 0) {
      std::snprintf(angle, sizeof angle, "%g", job.slab_mesh->needles->needle_angle_degrees);
      done.push_back("collapsed " + count(curve.needle_collapses, "short edge", "short edges") + " of needles (an angle under " + angle +
                     " degrees) or of triangles folded over their neighbours");
    }
    std::string said = done[0];
    for (size_t k = 1; k < done.size(); ++k) said += (k + 1 == done.size() ? " and " : ", ") + done[k];
    std::fprintf(stderr, "%s: note: %s, where the slabs would fold (--keep-faces keeps the mesh as it is)\n", a.input.c_str(),
                 said.c_str());
  }

  require_memory_for(a, variable, constant ? constant_wire_triangles(curve.cycle.num_triangles(), constant_options)
                                  : variable_wire_triangles(curve.cycle.num_triangles(), variable),
                     curve.cycle.num_triangles());

  PolygonMesh wire;
  double radius_used = 0;
  bool known_clear = false;
  if (constant) {
    ConstantWire made = constant_wire(curve.quads, curve.cycle, constant_options);
    if (!(made.radius > 0)) throw TopologyError(a.input + ": the curve touches itself: no wire radius avoids a self-intersection");
    wire = std::move(made.mesh);
    radius_used = made.radius;
  } else {
    VariableWire made = about_input(a.input, [&] { return variable_wire(curve.quads, curve.cycle, variable); });
    wire = std::move(made.mesh);
    known_clear = made.clear;
  }
  log.lap("wire");

  const PrintabilityReport report = check_printability(
      wire, {.known_clear = known_clear, .thickness = shape == WireShape::wire, .required_thickness = a.min_thickness});
  log.lap("report");
  write_mesh(wire, a.output);
  log.lap("write wire");
  if (!a.report.empty()) write_bytes(a.report, printability_json(report) + "\n");
  std::string picture_written;
  if (!a.png.empty()) {
    Scene scene;
    scene.meshes.push_back({.mesh = std::move(wire), .color = {0.72f, 0.45f, 0.2f}});
    // A wire half sunk in its surface shows its outer half, and the surface hides the
    // wires behind it, as in the paper's figures. A ribbon lies in the surface, which
    // would hide it half the time: it is drawn alone.
    if (shape == WireShape::wire)
      scene.meshes.push_back({.mesh = cycle_triangles(curve.quads, curve.cycle), .color = {0.82f, 0.82f, 0.82f},
                              .style = occluder_style(a.picture)});
    picture_written = write_picture(scene, picture, a.picture, a.png);
    log.lap("render png");
  }
  std::string summary = a.output + ": " + printability_summary(report);
  if (constant) summary += " Radius " + std::to_string(radius_used) + (radius ? "." : " (auto).");
  if (report.self_intersecting) {
    // Say when no wire that follows the surface could be clear: the surface's own
    // triangles (the cycle's, as the wire follows them) cross each other.
    const std::vector<int32_t> crossing = crossing_cycle_triangles(curve.quads, curve.cycle);
    if (!crossing.empty())
      summary += " Note: the surface itself crosses itself (" + std::to_string(crossing.size()) +
                 " of the cycle's triangles, e.g. number " + std::to_string(crossing.front()) +
                 " of those `meander curve --triangles` writes with these options): a wire that follows it cannot be "
                 "clear there.";
  }
  std::fprintf(stderr, "%s\n", summary.c_str());
  if (!a.png.empty()) log.note("wrote " + picture_written);
}

} // namespace

Command add_wire_command(CLI::App& parent) {
  auto args = std::make_shared<WireArgs>();
  CLI::App* app = parent.add_subcommand("wire", "Make a wire or ribbon sculpture from the surface-covering curve (3D-printable)");
  app->add_option("IN", args->input, "input mesh (.obj .ply .stl .off .gltf .glb)")->required();
  app->add_option("-o,--output", args->output, "output mesh: .stl, .ply (binary), .obj, .off, .glb, .3mf")->required();
  app->add_option("--method", args->method, "constant: a polygon or line swept along the smooth curve; variable: trapezoids "
                                            "inside the cycle's triangles, smoothed by Catmull-Clark")
      ->check(CLI::IsMember({"constant", "variable"}))->capture_default_str();
  app->add_option("--shape", args->shape, "wire (closed tube) or ribbon (band on the surface)")->check(CLI::IsMember({"wire", "ribbon"}))->capture_default_str();
  add_curve_flags(*app, args->curve);
  CLI::Option* tree = app->get_option("--tree");
  tree->description(tree->get_description() + "; --method variable defaults to shaped: its slabs fold where the cycle "
                                              "crosses slivers");
  app->add_option("--radius", args->radius, "constant: tube radius or half the ribbon width in mesh units, or auto: the "
                                            "largest that does not self-intersect")->capture_default_str();
  app->add_option("--sides", args->sides, "constant wire: sides of the swept polygon")->check(CLI::Range(3, 64))->capture_default_str();
  app->add_option("--s", args->s, "variable: trapezoid size across the curve, 0..1 (1 covers the surface)")->check(CLI::Range(0.0, 1.0))->capture_default_str();
  app->add_option("--t", args->t, "variable: trapezoid size along the curve, 0..1")->check(CLI::Range(0.0, 1.0))->capture_default_str();
  app->add_option("--thickness", args->thickness, "variable wire: slab thickness in mesh units (0: half the local ribbon width)")->check(CLI::NonNegativeNumber)->capture_default_str();
  app->add_option("--cap-angle", args->cap_angle, "variable: first flip the long edge of flat triangles whose largest "
                                                  "angle exceeds this many degrees (180: flip none)")
      ->check(CLI::Range(90.0, 180.0))->capture_default_str();
  app->add_flag("--keep-faces", args->keep_faces, "variable: build on the mesh's faces as they are, without splitting "
                                                  "polygons of 5 or more sides into triangles, flipping flat triangles or "
                                                  "collapsing the short edges of needles and of triangles folded over");
  app->add_option("--levels", args->levels, "variable: Catmull-Clark subdivision levels")->check(CLI::Range(0, 6))->capture_default_str();
  app->add_option("--min-thickness", args->min_thickness, "wire: the thinnest wall the printer makes, in mesh units "
                                                          "(about twice the nozzle width); thinner is reported as not printable")
      ->check(CLI::NonNegativeNumber);
  app->add_option("--report", args->report, "also write the printability report (.json)");
  CLI::Option* png = app->add_option("--png", args->png, "also render the result to this picture (.png); a wire's surface hides its back parts");
  add_picture_options(*app, args->picture, "the --png picture", png);
  app->add_flag("--strict", args->strict, "refuse a mesh that needs repair instead of repairing it");
  app->add_flag("-v,--verbose", args->verbose, "print the time each stage took");
  return {app, [args, tree] {
            if (args->method == "variable" && tree->count() == 0) args->curve.tree = "shaped";
            run_wire(*args);
          }};
}

} // namespace meander::cli
