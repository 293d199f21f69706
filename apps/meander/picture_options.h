// The picture options shared by `meander render` and the --png option of the producing
// subcommands: size, view, framing, turntable, curve and occluder style.
#pragma once

#include "meander/render.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>

namespace meander::cli {

struct PictureArgs {
  std::string size = "1600x1200", view = "iso", background = "white";
  std::string curve_style = "tube", occluder_style = "hidden";
  double curve_width = 0;
  bool fit = false;
  int32_t turntable = 0; // frames; 0: one picture
};

// Adds --size, --view, --background, --fit, --turntable, --curve-width, --curve-style and
// --occluder-style to `app`. `picture` names the picture in the help ("the picture",
// "the --png picture"); if `needs` is set, each option is refused without it.
void add_picture_options(CLI::App& app, PictureArgs& args, const std::string& picture, CLI::Option* needs = nullptr);

// The render options they give. Throws UsageError for a bad size, view or background,
// so that commands can check them before any work.
RenderOptions picture_options(const PictureArgs& args);

// How the occluding surface is drawn (--occluder-style).
MeshStyle occluder_style(const PictureArgs& args);

// Renders the scene to `path`, or its turntable frames next to it, and says what was
// written ("out.png: 1600x1200 picture", "36 frames spin_000.png .. spin_035.png").
std::string write_picture(const Scene& scene, const RenderOptions& options, const PictureArgs& args,
                          const std::filesystem::path& path);

} // namespace meander::cli
