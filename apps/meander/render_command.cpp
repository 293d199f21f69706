#include "cli_support.h"
#include "commands.h"

#include "meander/error.h"
#include "meander/io.h"
#include "meander/render.h"

#include <array>
#include <memory>

namespace meander::cli {

namespace {

struct RenderArgs {
  std::vector<std::string> inputs, occluders;
  std::string output, size = "1600x1200", view = "iso", background = "white";
  double curve_width = 0;
  int samples = 4;
  bool verbose = false;
};

// Curve files in turn get these colours, so that several curves can be told apart.
constexpr std::array<Rgb, 4> curve_colors{{{0.75f, 0.12f, 0.08f}, {0.1f, 0.3f, 0.75f}, {0.1f, 0.55f, 0.2f}, {0.85f, 0.55f, 0.05f}}};

void run_render(const RenderArgs& a) {
  RenderOptions options{.view = parse_view(a.view), .background = parse_background(a.background),
                        .samples = a.samples, .curve_width = a.curve_width};
  parse_size(a.size, options.width, options.height);
  require_output_path(a.output, {".png"}, "-o");

  StageLog log(a.verbose);
  Scene scene;
  for (const std::string& input : a.inputs) {
    // A file is a curve when it is not a mesh but holds polylines; if it holds neither,
    // the mesh reader's complaint is the one that explains it.
    try {
      scene.meshes.push_back({.mesh = read_mesh(input)});
    } catch (const InputError& mesh_error) {
      Polylines curves;
      try {
        curves = read_polylines(input);
      } catch (const Error&) {
        throw mesh_error;
      }
      scene.curves.push_back({.curves = std::move(curves), .color = curve_colors[scene.curves.size() % curve_colors.size()]});
    }
  }
  for (const std::string& occluder : a.occluders)
    scene.meshes.push_back({.mesh = read_mesh(occluder), .occluder_only = true});
  log.lap("read");
  const Image image = render(scene, options);
  log.lap("render");
  write_png(image, a.output);
  log.lap("write png");
  log.note("wrote " + a.output + ": " + std::to_string(image.width) + "x" + std::to_string(image.height));
}

} // namespace

Command add_render_command(CLI::App& parent) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* app = parent.add_subcommand("render", "Render meshes and curves to a PNG picture (ray traced on the CPU)");
  app->add_option("IN", args->inputs, "meshes (.obj .ply .stl .off) and curves (.obj with l elements)")->required();
  app->add_option("-o,--output", args->output, "output picture (.png)")->required();
  app->add_option("--size", args->size, "picture size in pixels, WIDTHxHEIGHT")->capture_default_str();
  app->add_option("--view", args->view, "front, back, left, right, top, iso, or AZ,EL in degrees")->capture_default_str();
  app->add_option("--background", args->background, "white, transparent or #rrggbb")->capture_default_str();
  app->add_option("--occluder", args->occluders, "a mesh that hides what is behind it but is not drawn");
  app->add_option("--curve-width", args->curve_width, "tube diameter in pixels (default: from the curve spacing)")->check(CLI::PositiveNumber);
  app->add_option("--samples", args->samples, "rays per pixel (anti-aliasing)")->check(CLI::Range(1, 1024))->capture_default_str();
  app->add_flag("-v,--verbose", args->verbose, "print the time each stage took");
  return {app, [args] { run_render(*args); }};
}

} // namespace meander::cli
