#include "cli_support.h"
#include "commands.h"

#include "meander/io.h"
#include "meander/shapes.h"

#include <cstdio>
#include <memory>
#include <optional>

namespace meander::cli {

namespace {

struct GenerateArgs {
  std::string shape, output;
  int64_t faces = 20000;
  int genus = 2;
  std::optional<uint64_t> shuffle;
};

} // namespace

Command add_generate_command(CLI::App& parent) {
  auto args = std::make_shared<GenerateArgs>();
  CLI::App* app = parent.add_subcommand("generate", "Write a mesh made by code (the demo model, test and benchmark inputs)");
  app->add_option("SHAPE", args->shape, "sphere, torus, pretzel (genus 2), genus (see --genus), grid (open disk), moebius")
      ->required()
      ->check(CLI::IsMember({"sphere", "torus", "pretzel", "genus", "grid", "moebius"}));
  app->add_option("-o,--output", args->output, "output mesh (.obj .ply .stl .off .glb)")->required();
  app->add_option("--faces", args->faces, "about how many faces")->check(CLI::Range(int64_t(1), int64_t(500'000'000)))->capture_default_str();
  app->add_option("--genus", args->genus, "genus of the 'genus' shape")->check(CLI::Range(0, 64))->capture_default_str();
  app->add_option("--shuffle", args->shuffle,
                  "write the vertices and faces in a random order from this seed, as some tools do (a scattered input)");
  return {app, [args] {
            require_output_path(args->output, {".obj", ".ply", ".stl", ".off", ".glb"}, "-o");
            PolygonMesh mesh = make_shape(args->shape, args->faces, args->genus);
            if (args->shuffle) mesh = shuffled(mesh, *args->shuffle);
            write_mesh(mesh, args->output);
            std::fprintf(stderr, "wrote %s: %s, %d vertices, %d faces\n", args->output.c_str(), args->shape.c_str(),
                         mesh.num_vertices(), mesh.num_faces());
          }};
}

} // namespace meander::cli
