#include "picture_options.h"

#include "meander/io.h"

namespace meander::cli {

void add_picture_options(CLI::App& app, PictureArgs& args, const std::string& picture, CLI::Option* needs) {
  CLI::Option* options[] = {
      app.add_option("--size", args.size, "size of " + picture + " in pixels, WIDTHxHEIGHT")->capture_default_str(),
      app.add_option("--view", args.view, "view of " + picture + ": front, back, left, right, top, iso, or AZ,EL in degrees")
          ->capture_default_str(),
      app.add_option("--background", args.background, "background of " + picture + ": white, transparent or #rrggbb")
          ->capture_default_str(),
      app.add_flag("--fit", args.fit,
                   "frame " + picture + " tightly on the object's outline as seen from the view (default: a margin "
                   "around the extent of the scene)"),
      app.add_option("--turntable", args.turntable,
                     "write N frames turning around the vertical axis instead of " + picture +
                         ": NAME_000.png, NAME_001.png ... at one distance framed on the bounding sphere")
          ->check(CLI::Range(1, 100000)),
      app.add_option("--curve-width", args.curve_width,
                     "curve diameter in pixels (default: a quarter of the spacing between neighbouring passes)")
          ->check(CLI::PositiveNumber),
      app.add_option("--curve-style", args.curve_style,
                     "tube (round, thicker nearer the eye) or ribbon (flat, the same width in pixels at any depth)")
          ->check(CLI::IsMember({"tube", "ribbon"}))
          ->capture_default_str(),
      app.add_option("--occluder-style", args.occluder_style,
                     "how the occluding surface shows: hidden (not drawn, as in the paper's figures), faint (a very "
                     "light grey) or shaded; parts of curves behind it are never drawn")
          ->check(CLI::IsMember({"hidden", "faint", "shaded"}))
          ->capture_default_str(),
  };
  // Turntable frames are framed on the bounding sphere, which keeps the distance fixed;
  // a tight frame would change it from frame to frame.
  options[3]->excludes(options[4]);
  if (needs)
    for (CLI::Option* option : options) option->needs(needs);
}

RenderOptions picture_options(const PictureArgs& args) {
  RenderOptions options{.view = parse_view(args.view),
                        .background = parse_background(args.background),
                        .curve_width = args.curve_width,
                        .curve_style = args.curve_style == "ribbon" ? CurveStyle::ribbon : CurveStyle::tube,
                        .framing = args.fit ? Framing::silhouette : Framing::bounds};
  parse_size(args.size, options.width, options.height);
  return options;
}

MeshStyle occluder_style(const PictureArgs& args) {
  return args.occluder_style == "faint"    ? MeshStyle::faint
         : args.occluder_style == "shaded" ? MeshStyle::shaded
                                           : MeshStyle::hidden;
}

std::string write_picture(const Scene& scene, const RenderOptions& options, const PictureArgs& args,
                          const std::filesystem::path& path) {
  const std::string size = std::to_string(options.width) + "x" + std::to_string(options.height);
  if (args.turntable == 0) {
    write_png(render(scene, options), path);
    return path.string() + ": " + size + " picture";
  }
  const auto frames = write_turntable(scene, options, args.turntable, path);
  return std::to_string(frames.size()) + " frames " + frames.front().string() + " .. " + frames.back().string() +
         ": " + size + " each";
}

} // namespace meander::cli
