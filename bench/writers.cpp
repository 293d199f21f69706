// meander_bench_writers [--faces N] [--benchmark_... flags]: write_mesh of a generated
// sphere of about N triangles (default 3,000,000) to binary STL and binary PLY in
// $TMPDIR, atomically as the CLI writes them (temporary file, then rename over the
// previous one). Google Benchmark, wall-clock time, 9 repetitions, median reported, with
// triangles per second ("items_per_second") and bytes per second. Issue 4's target:
// >= 20 M triangles per second for both.
#include "meander/io.h"
#include "meander/shapes.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

void write_file(benchmark::State& state, const meander::PolygonMesh& mesh, const std::filesystem::path& path) {
  for (auto _ : state) meander::write_mesh(mesh, path);
  const int64_t triangles = int64_t(mesh.num_corners()) - 2 * int64_t(mesh.num_faces());
  state.SetItemsProcessed(int64_t(state.iterations()) * triangles);
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
  state.counters["triangles"] = double(triangles);
}

} // namespace

int main(int argc, char** argv) {
  int64_t faces = 3'000'000;
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--faces") == 0 && i + 1 < argc) faces = std::atoll(argv[++i]);
    else rest.push_back(argv[i]);
  }
  int rest_count = int(rest.size());
  benchmark::Initialize(&rest_count, rest.data());
  const meander::PolygonMesh mesh = meander::sphere(faces);
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  const std::string stem = "meander_bench_writers_" + std::to_string(faces);
  std::vector<std::filesystem::path> outputs;
  for (const char* extension : {".stl", ".ply"}) {
    outputs.push_back(folder / (stem + extension));
    benchmark::RegisterBenchmark((std::string("write_binary") + extension).c_str(), write_file, mesh, outputs.back())
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Repetitions(9)
        ->ReportAggregatesOnly(true);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  for (const auto& path : outputs) std::filesystem::remove(path);
}
