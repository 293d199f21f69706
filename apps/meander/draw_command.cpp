#include "cli_support.h"
#include "commands.h"
#include "picture_options.h"

#include "meander/drawing.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/parameters.h"

#include <cstdio>
#include <memory>
#include <optional>

namespace meander::cli {

namespace {

struct DrawArgs {
  std::string input, output, occluder, png, paper = "A4", margin = "10mm", pen = "0.3mm";
  bool landscape = false;
  CurveJob job;
  int64_t max_faces = 0;
  PictureArgs picture;
  bool strict = false, verbose = false;
};

void run_draw(const DrawArgs& a) {
  CurveJob job = a.job;
  job.max_faces = a.max_faces;
  check_parameters(job);
  require_output_path(a.output, {".svg"}, "-o");
  if (!a.png.empty()) require_output_path(a.png, {".png"}, "--png");
  const RenderOptions picture = picture_options(a.picture);
  DrawingOptions options{.view = picture.view, .framing = picture.framing, .paper = parse_paper(a.paper, a.landscape)};
  options.paper.margin = millimetres("margin", a.margin);
  options.pen = millimetres("pen", a.pen);

  StageLog log(a.verbose);
  // A mesh gets its curve made; a curve file is drawn as it is, hidden by --occluder.
  Scene scene;
  std::optional<Polylines> curves;
  try {
    curves = read_polylines(a.input);
  } catch (const NoPolylinesError&) {
  } catch (const UsageError&) { // not a curve format: a mesh
  }
  if (curves) {
    scene.curves.push_back({.curves = std::move(*curves)});
    if (!a.occluder.empty()) scene.meshes.push_back({.mesh = read_mesh(a.occluder), .style = occluder_style(a.picture)});
    log.lap("read");
  } else {
    if (!a.occluder.empty()) throw UsageError("--occluder " + a.occluder + ": only a curve file takes one (" + a.input + " is a mesh, which hides its own curve)");
    job.cycle.count_leaves = a.verbose;
    const CurveResult result = make_input_curve(a.input, log, job, a.strict);
    log.note(leaves_note(result.cycle.leaves));
    scene = curve_scene(result, occluder_style(a.picture));
  }
  static const PolygonMesh no_surface;
  const Drawing drawing = draw_curves(scene.curves[0].curves, scene.meshes.empty() ? no_surface : scene.meshes[0].mesh, options);
  log.lap("draw");
  write_drawing(drawing, options.pen, a.output);
  std::string picture_written;
  if (!a.png.empty()) picture_written = write_picture(scene, picture, a.picture, a.png);
  log.lap("write");
  std::fprintf(stderr, "%s: %d path%s on %gx%g mm, %.0f mm drawn, %.0f mm with the pen up\n", a.output.c_str(), drawing.size(),
               drawing.size() == 1 ? "" : "s", drawing.paper.width, drawing.paper.height, drawing.drawn_length,
               drawing.travel);
  if (!a.png.empty()) log.note("wrote " + picture_written);
}

} // namespace

Command add_draw_command(CLI::App& parent) {
  auto args = std::make_shared<DrawArgs>();
  CLI::App* app = parent.add_subcommand(
      "draw", "Draw the curve for a pen plotter: an SVG of paths in millimetres on a sheet, the parts the surface hides removed");
  app->add_option("IN", args->input, "a mesh (its curve is made, with the curve's parameters) or a curve file (.obj .ply)")
      ->required();
  app->add_option("-o,--output", args->output, "output drawing (.svg)")->required();
  app->add_option("--occluder", args->occluder, "with a curve file: the surface that hides the curve's parts behind it");
  app->add_option("--paper", args->paper, "the sheet: A3, A4, A5, letter, legal or WIDTHxHEIGHT in mm")->capture_default_str();
  app->add_flag("--landscape", args->landscape, "turn the sheet to landscape");
  app->add_option("--margin", args->margin, "blank margin on each side of the sheet (mm, or with a unit)")->capture_default_str();
  app->add_option("--pen", args->pen, "the pen's width (mm, or with a unit): the stroke, and the detail kept")->capture_default_str();
  add_parameters(*app, args->job);
  add_max_faces(*app, args->max_faces);
  app->add_option("--png", args->png, "also render a preview picture (.png) from the same view");
  add_picture_options(*app, args->picture, "the drawing and its --png preview");
  app->add_flag("--strict", args->strict, "refuse a mesh that needs repair instead of repairing it");
  app->add_flag("-v,--verbose", args->verbose, "print the time each stage took");
  return {app, [args] { run_draw(*args); }};
}

} // namespace meander::cli
