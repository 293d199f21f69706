#include "cli_support.h"
#include "commands.h"
#include "picture_options.h"

#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/parameters.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace meander::cli {

namespace {

struct WireArgs {
  std::string input, output, report, png;
  WireJob job;
  int64_t max_faces = 0;
  PictureArgs picture;
  bool strict = false, verbose = false;
};

// Making and checking a wire takes 110 (constant wire) to 234 (variable ribbon) bytes
// per triangle at its peak, measured on the 100k-face sphere (docs/wires.md).
constexpr double kBytesPerTriangle = 240;

// Refuses a wire that would not fit in memory, naming the largest --levels that fits or
// the options to lower.
void require_memory_for(const WireArgs& a, int64_t cycle_triangles) {
  const WireJob& job = a.job;
  const int64_t triangles = wire_triangles(cycle_triangles, job);
  const auto what = [&] {
    return "the " + parameter_text(parameters::method, job.method) + " " + parameter_text(parameters::shape, job.shape) + " would have " + std::to_string(triangles) +
           " triangles";
  };
  const auto advice = [&](double memory) -> std::string {
    if (job.method != WireMethod::variable)
      return "lower --samples (" + std::to_string(job.curve.curve.samples) + ")" +
             (job.shape == WireShape::wire ? " or --sides (" + std::to_string(job.sides) + ")" : std::string()) +
             ", or use a coarser mesh";
    WireJob lower = job;
    while (--lower.levels >= 0)
      if (double(wire_triangles(cycle_triangles, lower)) * kBytesPerTriangle <= memory)
        return "use --levels " + std::to_string(lower.levels) + " or a coarser mesh";
    return "use a coarser mesh";
  };
  require_memory(a.input, double(triangles), kBytesPerTriangle, what, advice);
}

void run_wire(const WireArgs& a) {
  const WireJob& job = a.job;
  check_parameters(job);
  CurveJob curve_job = wire_curve_job(job);
  curve_job.max_faces = a.max_faces;
  curve_job.cycle.count_leaves = a.verbose;
  require_output_path(a.output, {".stl", ".ply", ".obj", ".off", ".glb", ".3mf"}, "-o");
  if (!a.report.empty()) require_output_path(a.report, {".json"}, "--report");
  if (!a.png.empty()) require_output_path(a.png, {".png"}, "--png");
  const RenderOptions picture = picture_options(a.picture);

  StageLog log(a.verbose);
  const CurveResult curve = make_input_curve(a.input, log, curve_job, a.strict);
  log.note(leaves_note(curve.cycle.leaves));
  StageTimes times;
  if (const std::vector<std::string> notes = slab_mesh_notes(curve, job); !notes.empty()) {
    std::string said = notes[0];
    for (size_t k = 1; k < notes.size(); ++k) said += (k + 1 == notes.size() ? " and " : ", ") + notes[k];
    std::fprintf(stderr, "%s: note: %s, where the slabs would fold (--keep-faces keeps the mesh as it is)\n", a.input.c_str(),
                 said.c_str());
  }
  require_memory_for(a, curve.cycle.num_triangles());
  WireResult wire = about_input(a.input, [&] { return make_wire(curve, job, &times); });
  for (const auto& [stage, seconds] : times) log.add(stage, seconds);
  log.restart();

  write_mesh(wire.mesh, a.output, {.millimetres = job.curve.model_size.has_value()});
  log.lap("write wire");
  const PrintabilityReport& report = wire.report;
  if (!a.report.empty()) write_bytes(a.report, wire_report_json(wire, job) + "\n");
  std::string picture_written;
  if (!a.png.empty()) {
    picture_written = write_picture(wire_scene(std::move(wire.mesh), curve, job, occluder_style(a.picture), wire.bridge_faces), picture,
                                    a.picture, a.png);
    log.lap("render png");
  }
  std::string summary = a.output + ": " + printability_summary(report);
  if (job.method == WireMethod::constant) summary += " Radius " + parameter_text(parameters::radius, wire.radius) + (job.radius ? "." : " (auto).");
  if (job.bridges) {
    const BridgePlan& bridges = wire.bridges;
    summary += " Bridges: " + std::to_string(bridges.ends.size()) + ", the longest stretch without one " +
               parameter_text(parameters::bridges, std::optional(bridges.longest_stretch)) + " (asked " +
               parameter_text(parameters::bridges, job.bridges) + "): " +
               (bridges.every_pass_tied ? "every pass is tied to the rest."
                     : bridges.one_piece ? "some passes are not tied (no neighbouring pass near enough, or in the way)."
                                         : "the curves are not all joined into one piece.");
  }
  if (!wire.surface_crossings.empty())
    summary += " Note: the surface itself crosses itself (" + std::to_string(wire.surface_crossings.size()) +
               " of the cycle's triangles, e.g. number " + std::to_string(wire.surface_crossings.front()) +
               " of those `meander curve --triangles` writes with these options): a wire that follows it cannot be "
               "clear there.";
  std::fprintf(stderr, "%s\n", summary.c_str());
  if (!a.png.empty()) log.note("wrote " + picture_written);
}

} // namespace

Command add_wire_command(CLI::App& parent) {
  auto args = std::make_shared<WireArgs>();
  CLI::App* app = parent.add_subcommand("wire", "Make a wire or ribbon sculpture from the surface-covering curve (3D-printable)");
  app->add_option("IN", args->input, "input mesh (.obj .ply .stl .off .gltf .glb)")->required();
  app->add_option("-o,--output", args->output, "output mesh: .stl, .ply (binary), .obj, .off, .glb, .3mf")->required();
  add_parameters(*app, args->job);
  add_max_faces(*app, args->max_faces);
  CLI::Option* tree = app->get_option("--tree");
  tree->description(tree->get_description() + "; --method variable defaults to shaped: its slabs fold where the cycle "
                                              "crosses slivers");
  app->add_option("--report", args->report, "also write the printability report (.json)");
  CLI::Option* png = app->add_option("--png", args->png, "also render the result to this picture (.png); a wire's surface hides its back parts");
  add_picture_options(*app, args->picture, "the --png picture", png);
  app->add_flag("--strict", args->strict, "refuse a mesh that needs repair instead of repairing it");
  app->add_flag("-v,--verbose", args->verbose, "print the time each stage took");
  return {app, [args, tree] {
            if (args->job.method == WireMethod::variable && tree->count() == 0) args->job.curve.cycle.tree = TreeStrategy::shaped;
            run_wire(*args);
          }};
}

} // namespace meander::cli
