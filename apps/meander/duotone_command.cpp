#include "cli_support.h"
#include "commands.h"
#include "picture_options.h"

#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/parameters.h"
#include "meander/textured_io.h"

#include <cmath>
#include <cstdio>
#include <memory>

namespace meander::cli {

namespace {

struct DuotoneArgs {
  std::string input, output, png, curve, regions, parts;
  DuotoneJob job;
  int64_t max_faces = 0;
  PictureArgs picture;
  bool strict = false, verbose = false;
};

// "A.ply,B.ply" -> the two paths.
std::array<std::string, 2> two_paths(const std::string& text, const char* option, const char* example) {
  const size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos || comma == 0 || comma + 1 == text.size())
    throw UsageError(std::string(option) + " '" + text + "': expected two files " + example + " (one per colour)");
  return {text.substr(0, comma), text.substr(comma + 1)};
}

// A subdivided duotone surface took 435 to 451 bytes per quad at its peak, written as
// OBJ, on the 100k-face sphere at --subdivide 2 and 3 (docs/duotone.md).
constexpr double kBytesPerQuad = 480;

void run_duotone(const DuotoneArgs& a) {
  DuotoneJob job = a.job;
  job.max_faces = a.max_faces;
  check_parameters(job);
  const bool print = lowercase_extension(a.output) == ".3mf";
  require_output_path(a.output, {".obj", ".glb", ".3mf"}, "-o");
  if (print && !job.shell)
    throw UsageError("-o " + a.output + ": a .3mf is the two-colour print, a shell (add --shell, its wall's thickness)");
  if (!a.parts.empty() && !job.shell) throw UsageError("--parts: the two solids are those of a shell (add --shell)");
  if (job.shell && !print && a.parts.empty())
    throw UsageError("--shell makes a two-colour print: write it with -o OUT.3mf or --parts A.stl,B.stl");
  std::array<std::string, 2> parts;
  if (!a.parts.empty()) {
    parts = two_paths(a.parts, "--parts", "A.stl,B.stl");
    for (const std::string& path : parts) require_output_path(path, {".stl", ".3mf", ".obj", ".ply", ".off", ".glb"}, "--parts");
  }
  if (!a.curve.empty()) require_output_path(a.curve, {".obj", ".ply", ".json", ".svg"}, "--curve");
  std::array<std::string, 2> regions;
  if (!a.regions.empty()) {
    regions = two_paths(a.regions, "--regions", "A.ply,B.ply");
    for (const std::string& path : regions) require_output_path(path, {".ply"}, "--regions");
  }
  if (!a.png.empty()) require_output_path(a.png, {".png"}, "--png");
  const RenderOptions picture = picture_options(a.picture);

  StageLog log(a.verbose);
  const RepairResult input = read_and_repair(a.input, log, {.strict = a.strict, .max_faces = a.max_faces});
  require_memory_for_spacing(a.input, input.mesh, job.model_size, job.spacing, job.duotone.quadrangulation);
  log.restart();
  const Duotone duotone = about_input(a.input, [&] { return make_duotone(input.mesh, input.connectivity, job); });
  for (const std::string& note : duotone.notes) std::fprintf(stderr, "%s: note: %s\n", a.input.c_str(), note.c_str());
  log.lap("duotone");
  const auto quads_at = [&](int levels) { return double(duotone.quads.num_quads()) * std::pow(4.0, levels); };
  require_memory(
      a.input, quads_at(job.subdivide), kBytesPerQuad,
      [&] {
        return "the duotone surface at --subdivide " + std::to_string(job.subdivide) + " would have " +
               std::to_string(int64_t(quads_at(job.subdivide))) + " quads";
      },
      [&](double memory) -> std::string {
        for (int levels = job.subdivide - 1; levels >= 0; --levels)
          if (quads_at(levels) * kBytesPerQuad <= memory) return "use --subdivide " + std::to_string(levels) + " or a coarser mesh";
        return "use a coarser mesh";
      });
  StageTimes times;
  const bool painted = !print || !a.png.empty() || lowercase_extension(a.curve) == ".svg";
  const TexturedMesh surface = painted ? paint_duotone(duotone, job, {}, &times) : TexturedMesh{};
  for (const auto& [stage, seconds] : times) log.add(stage, seconds);
  log.restart();
  std::optional<SplitShell> shell;
  if (job.shell) {
    shell = about_input(a.input, [&] { return make_shell(duotone, job); });
    log.lap("shell");
  }
  // Everything is computed before the first file is written, so that a refusal leaves
  // no output behind.
  Polylines curves;
  if (!a.curve.empty()) curves = separating_curves(duotone, job.tiles.style);
  std::array<PolygonMesh, 2> pieces;
  if (!a.regions.empty()) pieces = duotone_regions(duotone, job.tiles.style);
  const bool curve_drawing = lowercase_extension(a.curve) == ".svg";
  const std::string drawing = curve_drawing ? curve_svg(curves, surface.mesh, job.model_size.has_value()) : "";
  log.lap("curve, regions");

  if (print) write_3mf_parts(colored_parts(shell->solids[0], shell->solids[1], job.tiles.colors), a.output);
  else write_textured_mesh(surface, a.output, job.model_size.has_value());
  for (int k = 0; k < 2 && !a.parts.empty(); ++k)
    write_mesh(shell->solids[size_t(k)], parts[size_t(k)], {.millimetres = job.model_size.has_value()});
  if (curve_drawing) write_bytes(a.curve, drawing);
  else if (!a.curve.empty()) write_polylines(curves, a.curve);
  for (int k = 0; k < 2 && !a.regions.empty(); ++k) write_mesh(pieces[size_t(k)], regions[size_t(k)]);
  log.lap("write");
  std::string picture_written;
  if (!a.png.empty()) {
    picture_written = write_picture(duotone_scene(surface), picture, a.picture, a.png);
    log.lap("render png");
  }
  const int32_t components = duotone.cycle.num_cycles();
  const std::string regions_text = components == 1 ? "2 colour regions and 1 separating curve"
                                                   : std::to_string(components) + " components, each 2 colour regions and 1 separating curve";
  std::fprintf(stderr, "%s: %d quads (%s), %s, %s tiles\n", a.output.c_str(), duotone.quads.num_quads(),
               duotone.quadrangulation == Quadrangulation::catmull_clark ? "catmull-clark"
               : duotone.quadrangulation == Quadrangulation::dual_simplest ? "dual-simplest" : "as is",
               regions_text.c_str(), std::string(to_string(job.tiles.style)).c_str());
  if (shell) std::fprintf(stderr, "%s\n", shell_summary(*shell, job).c_str());
  if (!a.png.empty()) log.note("wrote " + picture_written);
}

} // namespace

Command add_duotone_command(CLI::App& parent) {
  auto args = std::make_shared<DuotoneArgs>();
  CLI::App* app = parent.add_subcommand("duotone", "Paint a surface in two colours: two connected regions separated by one curve per component (Truchet tiles)");
  app->add_option("IN", args->input, "input mesh (.obj .ply .stl .off .gltf .glb)")->required();
  app->add_option("-o,--output", args->output,
                  "textured surface: .obj (with .mtl and a .png texture beside it) or .glb; with --shell, .3mf: the "
                  "two-colour print (two solids, one per extruder)")
      ->required();
  add_parameters(*app, args->job);
  app->add_option("--curve", args->curve, "also write the separating curve(s) on the quad surface: .obj, .ply, .json, .svg");
  app->add_option("--regions", args->regions, "also write the two colour regions cut along the curve: A.ply,B.ply (binary)");
  app->add_option("--parts", args->parts, "with --shell: write the two solids apart, A.stl,B.stl (any mesh format)");
  CLI::Option* png = app->add_option("--png", args->png, "also render the textured surface to this picture (.png)");
  add_picture_options(*app, args->picture, "the --png picture", png);
  add_max_faces(*app, args->max_faces);
  app->add_flag("--strict", args->strict, "refuse a mesh that needs repair instead of repairing it");
  app->add_flag("-v,--verbose", args->verbose, "print the time each stage took and what was written");
  return {app, [args] { run_duotone(*args); }};
}

} // namespace meander::cli
