// meander: Hamiltonian cycle art from the command line.
// Exit codes: 0 success, 1 input refused or processing failed, 2 usage error.
#include "cli_support.h"
#include "commands.h"

#include "meander/error.h"

#include <cstdio>
#include <new>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  CLI::App app{"Meander turns any polygon mesh into one closed curve that meanders over its whole surface."};
  app.require_subcommand(1);
  app.fallthrough(false);
  using namespace meander::cli;
  const std::vector<Command> commands = {add_curve_command(app), add_info_command(app), add_generate_command(app),
                                         add_render_command(app), add_wire_command(app),
                                         add_serve_command(app), add_duotone_command(app), add_draw_command(app),
                                         add_image_command(app)};
  try {
    app.parse(argc, argv);
    for (const Command& c : commands)
      if (c.app->parsed()) c.run();
    return 0;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const meander::ParameterError& e) {
    // The library names the parameter; here it is an option.
    const std::string message = e.what();
    std::fprintf(stderr, "meander: %s%s\n", option_name(e.parameter()).c_str(), message.c_str() + e.parameter().size());
    return 2;
  } catch (const meander::UsageError& e) {
    std::fprintf(stderr, "meander: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "meander: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meander: %s\n", e.what());
    return 1;
  }
}
