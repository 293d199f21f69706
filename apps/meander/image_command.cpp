#include "cli_support.h"
#include "commands.h"

#include "meander/drawing.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/jobs.h"
#include "meander/parameters.h"
#include "meander/render.h"
#include "meander/textured_io.h"

#include <algorithm>
#include <cstdio>
#include <memory>

namespace meander::cli {

namespace {

struct ImageArgs {
  std::string input, output, duotone, png, size = "1600x1200";
  ImageJob job;
  bool verbose = false;
};

void run_image(const ImageArgs& a) {
  check_parameters(a.job);
  require_output_path(a.output, {".svg", ".obj", ".ply", ".png"}, "-o");
  if (!a.duotone.empty()) require_output_path(a.duotone, {".svg"}, "--duotone");
  if (!a.png.empty()) require_output_path(a.png, {".png"}, "--png");
  int32_t width = 0, height = 0;
  parse_size(a.size, width, height);

  StageLog log(a.verbose);
  const Texture picture = read_texture(a.input, a.job.max_pixels);
  log.lap("read");
  ImageJob job = a.job;
  job.cycle.count_leaves = a.verbose;
  StageTimes times;
  const LinePicture result = [&] {
    try {
      return make_line_picture(picture, job, &times);
    } catch (const InputError& e) {
      throw InputError(a.input + ": " + e.what());
    }
  }();
  for (const auto& [stage, seconds] : times) log.add(stage, seconds);
  log.restart();
  log.note(std::to_string(result.cells) + " cells");
  log.note(leaves_note(result.leaves));

  // Every file made before the first is written, so that a refusal leaves none behind.
  const Drawing& drawing = result.drawing;
  const auto png_of = [&] { return png_file_bytes(drawing_image(drawing, job.pen, width, height)); };
  const std::string extension = lowercase_extension(a.output);
  std::string out;
  if (extension == ".svg") {
    out = drawing_svg(drawing, job.pen);
  } else if (extension == ".png") {
    out = png_of();
  } else {
    out = polylines_file_bytes(line_picture_curve(result), a.output);
  }
  const std::string duotone = a.duotone.empty() ? "" : line_picture_duotone_svg(result, job);
  const std::string preview = a.png.empty() ? "" : png_of();
  write_bytes(a.output, out);
  if (!a.duotone.empty()) write_bytes(a.duotone, duotone);
  if (!a.png.empty()) write_bytes(a.png, preview);
  log.lap("write");
  std::fprintf(stderr, "%s: one closed line on %gx%g mm, %.0f mm long\n", a.output.c_str(), drawing.paper.width,
               drawing.paper.height, drawing.drawn_length);
}

} // namespace

Command add_image_command(CLI::App& parent) {
  auto args = std::make_shared<ImageArgs>();
  CLI::App* app = parent.add_subcommand(
      "image", "Draw a picture with one closed line that never crosses itself, denser where the picture is darker");
  app->add_option("PICTURE", args->input, "the picture (.png .jpg .bmp .tga .gif), read as its luma")->required();
  app->add_option("-o,--output", args->output,
                  "the drawing (.svg), its line as a curve file in millimetres (.obj .ply), or a picture of it (.png)")
      ->required();
  app->add_option("--duotone", args->duotone, "also write the two regions the line bounds, filled in --colors (.svg)");
  app->add_option("--png", args->png, "also write a picture of the drawing (.png)");
  app->add_option("--size", args->size, "the .png's largest size WxH in pixels (the sheet's proportions kept)")
      ->capture_default_str();
  add_parameters(*app, args->job);
  app->add_flag("-v,--verbose", args->verbose, "print the time each stage took");
  return {app, [args] { run_image(*args); }};
}

} // namespace meander::cli
