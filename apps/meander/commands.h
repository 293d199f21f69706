// The subcommands of the meander CLI. Each adds itself to the app and returns what to
// run when it was the one chosen; main() maps exceptions to exit codes.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace meander::cli {

struct Command {
  CLI::App* app;
  std::function<void()> run;
};

Command add_curve_command(CLI::App& parent);
Command add_info_command(CLI::App& parent);
Command add_generate_command(CLI::App& parent);
Command add_render_command(CLI::App& parent);
Command add_wire_command(CLI::App& parent);
Command add_duotone_command(CLI::App& parent);
Command add_serve_command(CLI::App& parent);
Command add_draw_command(CLI::App& parent);
Command add_image_command(CLI::App& parent);

} // namespace meander::cli
