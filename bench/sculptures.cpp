// meander_bench_sculptures FILE [--benchmark_... flags]: what `meander wire` and `meander
// duotone` compute between the curve and the file, on FILE read and repaired once:
//   constant_wire           constant_wire with the CLI's defaults (8 sides, 4 samples per
//                           segment, radius auto), on the default curve's cycle
//   variable_wire_levels_1  variable_wire at 1 Catmull-Clark level, automatic thickness,
//                           on the cycle `wire --method variable` makes (slab mesh, shaped tree)
//   duotone                 make_duotone and duotone_surface with the CLI's defaults
//                           (Catmull-Clark quads, tree rule, Truchet tiles, 1024-pixel atlas)
// The curves and the printability report are not timed. Google Benchmark, wall-clock
// time, median of 5 repetitions (3 for the variable wire), with the triangles (quads for
// the duotone) made per second.
#include "meander/check.h"
#include "meander/duotone.h"
#include "meander/io.h"
#include "meander/pipeline.h"
#include "meander/wire.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

namespace {

using namespace meander;

// The curve as `meander curve` makes it (the slab mesh and shaped tree of a variable wire
// when `slab` is set), without its sampled points.
CurveResult cycle_of(const RepairResult& input, bool slab) {
  CurveJob job{.sample = false};
  if (slab) {
    job.slab_mesh = SlabMeshOptions{};
    job.cycle.tree = TreeStrategy::shaped;
  }
  return make_curve(input.mesh, input.connectivity, job);
}

int64_t triangle_count(const PolygonMesh& mesh) { return int64_t(mesh.num_corners()) - 2 * int64_t(mesh.num_faces()); }

void made(benchmark::State& state, int64_t triangles) {
  state.SetItemsProcessed(int64_t(state.iterations()) * triangles);
  state.counters["triangles"] = double(triangles);
}

benchmark::internal::Benchmark* configure(benchmark::internal::Benchmark* b, int repetitions) {
  return b->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(repetitions)->ReportAggregatesOnly(true);
}

} // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (argc != 2) {
    std::fprintf(stderr, "usage: meander_bench_sculptures [--benchmark_... flags] FILE\n");
    return 2;
  }
  const std::filesystem::path path = argv[1];
  const std::string name = path.filename().string();
  RepairResult input;
  CurveResult curve, slab_curve;
  try {
    input = repair(read_mesh(path), path.string());
    if (input.connectivity.edge_start.empty()) input.connectivity = build_connectivity(input.mesh);
    curve = cycle_of(input, false);
    slab_curve = cycle_of(input, true);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meander_bench_sculptures: %s\n", e.what());
    return 1;
  }

  configure(benchmark::RegisterBenchmark(("constant_wire/" + name).c_str(),
                                         [&](benchmark::State& state) {
                                           int64_t triangles = 0;
                                           for (auto _ : state) {
                                             const ConstantWire wire = constant_wire(curve.quads, curve.cycle, {});
                                             triangles = triangle_count(wire.mesh);
                                           }
                                           made(state, triangles);
                                         }),
            5);
  configure(benchmark::RegisterBenchmark(("variable_wire_levels_1/" + name).c_str(),
                                         [&](benchmark::State& state) {
                                           int64_t triangles = 0;
                                           for (auto _ : state) {
                                             const VariableWire wire =
                                                 variable_wire(slab_curve.quads, slab_curve.cycle, {.levels = 1});
                                             triangles = triangle_count(wire.mesh);
                                           }
                                           made(state, triangles);
                                         }),
            3);
  configure(benchmark::RegisterBenchmark(("duotone/" + name).c_str(),
                                         [&](benchmark::State& state) {
                                           int64_t quads = 0;
                                           for (auto _ : state) {
                                             const Duotone duotone = make_duotone(input.mesh, input.connectivity);
                                             const TexturedMesh surface = duotone_surface(duotone, {});
                                             quads = surface.mesh.num_faces();
                                           }
                                           made(state, quads);
                                         }),
            5);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
