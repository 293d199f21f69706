#include "cli_support.h"
#include "commands.h"
#include "picture_options.h"

#include "meander/error.h"
#include "meander/io.h"
#include "meander/textured_io.h"
#include "meander/render.h"

#include <array>
#include <memory>

namespace meander::cli {

namespace {

struct RenderArgs {
  std::vector<std::string> inputs, occluders;
  std::string output;
  PictureArgs picture;
  int samples = 4;
  bool verbose = false;
};

// Curve files in turn get these colours, so that several curves can be told apart.
constexpr std::array<Rgb, 4> curve_colors{{{0.75f, 0.12f, 0.08f}, {0.1f, 0.3f, 0.75f}, {0.1f, 0.55f, 0.2f}, {0.85f, 0.55f, 0.05f}}};

// A file is a curve when it is not a mesh but holds polylines. If it holds neither, the
// mesh reader's complaint explains it; if its polylines are malformed, the curve
// reader's does.
void read_input(const std::string& input, Scene& scene) {
  try {
    TexturedMesh textured = read_textured_mesh(input);
    scene.meshes.push_back({.mesh = std::move(textured.mesh), .appearance = std::move(textured.appearance)});
  } catch (const InputError& mesh_error) {
    Polylines curves;
    try {
      curves = read_polylines(input);
    } catch (const NoPolylinesError&) {
      throw mesh_error;
    } catch (const InputError&) {
      throw;
    } catch (const Error&) {
      throw mesh_error;
    }
    scene.curves.push_back({.curves = std::move(curves), .color = curve_colors[scene.curves.size() % curve_colors.size()]});
  }
}

void run_render(const RenderArgs& a) {
  RenderOptions options = picture_options(a.picture);
  options.samples = a.samples;
  require_output_path(a.output, {".png"}, "-o");

  StageLog log(a.verbose);
  Scene scene;
  for (const std::string& input : a.inputs) read_input(input, scene);
  for (const std::string& occluder : a.occluders)
    scene.meshes.push_back({.mesh = read_mesh(occluder), .style = occluder_style(a.picture)});
  log.lap("read");
  const std::string written = write_picture(scene, options, a.picture, a.output);
  log.lap("render and write png");
  log.note("wrote " + written);
}

} // namespace

Command add_render_command(CLI::App& parent) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* app = parent.add_subcommand("render", "Render meshes and curves to a PNG picture (ray traced on the CPU)");
  app->add_option("IN", args->inputs, "meshes (.obj with its MTL and textures, .glb .gltf .ply .stl .off) and curves (.obj with l elements, .ply with edges)")
      ->required();
  app->add_option("-o,--output", args->output, "output picture (.png); with --turntable N, the frames' name")->required();
  app->add_option("--occluder", args->occluders,
                  "a mesh that hides the parts of the curves behind it, drawn as --occluder-style says");
  add_picture_options(*app, args->picture, "the picture");
  app->add_option("--samples", args->samples, "rays per pixel (anti-aliasing)")->check(CLI::Range(1, 1024))->capture_default_str();
  app->add_flag("-v,--verbose", args->verbose, "print the time each stage took");
  return {app, [args] { run_render(*args); }};
}

} // namespace meander::cli
