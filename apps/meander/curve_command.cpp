#include "cli_support.h"
#include "commands.h"
#include "picture_options.h"

#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/parameters.h"
#include "meander/render.h"

#include <memory>

namespace meander::cli {

namespace {

struct CurveArgs {
  std::string input, output, triangles, png;
  CurveJob job;
  int64_t max_faces = 0;
  PictureArgs picture;
  bool strict = false, verbose = false;
};

void run_curve(const CurveArgs& a) {
  CurveJob job = a.job;
  job.max_faces = a.max_faces;
  check_parameters(job);
  // Only the picture and the drawing need the curve's points in memory; otherwise they
  // are sampled as the file is written (on a 10M-triangle mesh, 1.44 GB never allocated).
  require_output_path(a.output, {".obj", ".ply", ".json", ".svg"}, "-o");
  const bool drawing = lowercase_extension(a.output) == ".svg";
  job.sample = !a.png.empty() || drawing;
  if (!drawing) job.output = a.output;
  job.cycle.count_leaves = a.verbose;
  if (!a.triangles.empty()) require_output_path(a.triangles, {".obj", ".ply", ".off", ".stl"}, "--triangles");
  if (!a.png.empty()) require_output_path(a.png, {".png"}, "--png");
  const RenderOptions picture = picture_options(a.picture);

  StageLog log(a.verbose);
  const CurveResult result = make_input_curve(a.input, log, job, a.strict);
  if (drawing) {
    write_bytes(a.output, curve_svg(result, job.model_size.has_value()));
    log.lap("draw + write");
  }
  const int64_t points = drawing ? int64_t(result.curves.points.size()) : result.points_written;
  if (!a.triangles.empty()) {
    write_mesh(cycle_triangles(result.quads, result.cycle), a.triangles, {.group_start = result.cycle.cycle_start});
    log.lap("write cycle");
  }
  std::string picture_written;
  if (!a.png.empty()) {
    picture_written = write_picture(curve_scene(result, occluder_style(a.picture)), picture, a.picture, a.png);
    log.lap("render png");
  }
  const int32_t curves = result.cycle.num_cycles();
  log.note(leaves_note(result.cycle.leaves));
  log.note("wrote " + a.output + ": " + std::to_string(curves) + " closed curve" + (curves == 1 ? "" : "s") + ", " +
           std::to_string(points) + " points");
  if (!a.triangles.empty())
    log.note("wrote " + a.triangles + ": " + std::to_string(result.cycle.num_triangles()) +
             " triangles in cycle order");
  if (!a.png.empty()) log.note("wrote " + picture_written);
}

} // namespace

Command add_curve_command(CLI::App& parent) {
  auto args = std::make_shared<CurveArgs>();
  CLI::App* app = parent.add_subcommand("curve", "Make the closed curve(s) that cover a mesh's surface (one per connected component)");
  app->add_option("IN", args->input, "input mesh (.obj .ply .stl .off .gltf .glb)")->required();
  app->add_option("-o,--output", args->output,
                  "output curve: .obj (l elements), .ply (binary edges), .json, or .svg: a plotter drawing seen from the "
                  "front, the surface hiding its back parts (meander draw chooses the view and sheet)")
      ->required();
  add_parameters(*app, args->job);
  add_max_faces(*app, args->max_faces);
  app->add_option("--triangles", args->triangles, "also write the certificate: the triangulated quad mesh, faces in cycle order, one OBJ group per cycle");
  CLI::Option* png = app->add_option(
      "--png", args->png, "also render the curve to this picture (.png), the surface hiding its back parts");
  add_picture_options(*app, args->picture, "the --png picture", png);
  app->add_flag("--strict", args->strict, "refuse a mesh that needs repair instead of repairing it");
  app->add_flag("-v,--verbose", args->verbose, "print the time each stage took and what was written");
  return {app, [args] { run_curve(*args); }};
}

} // namespace meander::cli
