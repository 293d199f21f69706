// meander_bench_peers [--benchmark_... flags] FILE... (or MEANDER_BENCH_MESH=FILE): Meander
// and its peers load the same files in the same run, each benchmark repeated 5 times.
// Per file:
//   meander_read                      read_mesh
//   meander_read_connectivity         read_mesh + build_connectivity
//   meander_read_check_connectivity   read_mesh + repair, whose connectivity the pipeline
//                                     takes over (built again only if repair re-oriented
//                                     faces): what `meander curve` does before it
//                                     quadrangulates
//   openmesh_read                     OpenMesh::IO::read_mesh into a PolyMesh_ArrayKernelT,
//                                     which builds its halfedge connectivity while reading
//                                     and refuses non-manifold faces: the peer of read +
//                                     connectivity (and of read + check + connectivity)
//   tinyobj_load (OBJ files only)     tinyobj::LoadObj without triangulation, a parse into
//                                     flat arrays like read_mesh: the peer of read_mesh
// Every load builds and frees its mesh inside the timed loop. After the usual console
// output come markdown tables of the median real times with the peer / Meander ratios.
#include "meander/check.h"
#include "meander/connectivity.h"
#include "meander/io.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <benchmark/benchmark.h>
#include <tiny_obj_loader.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace {

using Path = std::filesystem::path;

// Each load returns the number of faces it read, so that a peer that drops or splits
// faces is caught instead of being timed on a different mesh.
int64_t meander_read(const Path& path) { return meander::read_mesh(path).num_faces(); }

int64_t meander_read_connectivity(const Path& path) {
  const meander::PolygonMesh mesh = meander::read_mesh(path);
  const meander::Connectivity connectivity = meander::build_connectivity(mesh);
  benchmark::DoNotOptimize(connectivity.edge_start.data());
  return mesh.num_faces();
}

// As the pipeline does: repair's connectivity when it kept one, else a new one.
int64_t meander_read_check_connectivity(const Path& path) {
  meander::RepairResult repaired = meander::repair(meander::read_mesh(path), path.string());
  if (repaired.connectivity.edge_start.empty()) repaired.connectivity = meander::build_connectivity(repaired.mesh);
  benchmark::DoNotOptimize(repaired.connectivity.edge_start.data());
  return repaired.mesh.num_faces();
}

int64_t openmesh_read(const Path& path) {
  OpenMesh::PolyMesh_ArrayKernelT<> mesh;
  return OpenMesh::IO::read_mesh(mesh, path.string()) ? int64_t(mesh.n_faces()) : -1;
}

int64_t tinyobj_load(const Path& path) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, path.c_str(), nullptr, /*triangulate=*/false))
    return -1;
  int64_t faces = 0;
  for (const tinyobj::shape_t& shape : shapes) faces += int64_t(shape.mesh.num_face_vertices.size());
  return faces;
}

struct Loader {
  const char* name;
  int64_t (*load)(const Path&);
  bool obj_only;
};

constexpr Loader loaders[] = {
    {"meander_read", meander_read, false},
    {"meander_read_connectivity", meander_read_connectivity, false},
    {"meander_read_check_connectivity", meander_read_check_connectivity, false},
    {"openmesh_read", openmesh_read, false},
    {"tinyobj_load", tinyobj_load, true},
};

struct Input {
  Path path;
  int64_t faces = 0;
  int64_t triangles = 0; // an n-gon counts as n - 2
  bool obj = false;
};

void run_load(benchmark::State& state, const Input& input, int64_t (*load)(const Path&)) {
  for (auto _ : state) {
    const int64_t faces = load(input.path);
    if (faces != input.faces) {
      state.SkipWithError(("read " + std::to_string(faces) + " faces where Meander reads " +
                           std::to_string(input.faces) + ": not the same mesh")
                              .c_str());
      break;
    }
  }
}

std::string benchmark_name(const Loader& loader, const Input& input) {
  return std::string(loader.name) + "/" + input.path.filename().string();
}

// The console output as usual, keeping each benchmark's median real time (ms).
class MedianReporter : public benchmark::ConsoleReporter {
public:
  // A custom display reporter does not get --benchmark_color: colour only on a terminal.
  MedianReporter() : ConsoleReporter(isatty(STDOUT_FILENO) ? OO_Defaults : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs)
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median" && !run.error_occurred)
        medians_[run.run_name.function_name] = run.GetAdjustedRealTime();
  }
  // The median of `loader` on `input`, or nothing if it did not run (filtered out, failed).
  const double* median(const Loader& loader, const Input& input) const {
    const auto it = medians_.find(benchmark_name(loader, input));
    return it == medians_.end() ? nullptr : &it->second;
  }

private:
  std::map<std::string, double> medians_;
};

void print_time(const double* ms) {
  if (ms) std::printf(" %.1f ms |", *ms);
  else std::printf(" - |");
}

void print_ratio(const double* peer, const double* meander) {
  if (peer && meander) std::printf(" %.1fx |", *peer / *meander);
  else std::printf(" - |");
}

void print_tables(const MedianReporter& r, const std::vector<Input>& inputs) {
  const Loader &read = loaders[0], &connectivity = loaders[1], &checked = loaders[2], &openmesh = loaders[3],
               &tinyobj = loaders[4];
  std::printf("\n| mesh | triangles | Meander read | Meander read + connectivity | Meander read + check + "
              "connectivity | OpenMesh read_mesh | OpenMesh / (read + connectivity) | OpenMesh / (read + check + "
              "connectivity) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Input& in : inputs) {
    std::printf("| %s | %lld |", in.path.filename().c_str(), (long long)in.triangles);
    for (const Loader* l : {&read, &connectivity, &checked, &openmesh}) print_time(r.median(*l, in));
    print_ratio(r.median(openmesh, in), r.median(connectivity, in));
    print_ratio(r.median(openmesh, in), r.median(checked, in));
    std::printf("\n");
  }
  bool any_obj = false;
  for (const Input& in : inputs) any_obj |= in.obj;
  if (!any_obj) return;
  std::printf("\n| OBJ file | triangles | Meander read | tinyobjloader LoadObj | tinyobjloader / Meander |\n"
              "|---|---:|---:|---:|---:|\n");
  for (const Input& in : inputs) {
    if (!in.obj) continue;
    std::printf("| %s | %lld |", in.path.filename().c_str(), (long long)in.triangles);
    print_time(r.median(read, in));
    print_time(r.median(tinyobj, in));
    print_ratio(r.median(tinyobj, in), r.median(read, in));
    std::printf("\n");
  }
}

} // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  std::vector<Input> inputs;
  try {
    std::vector<Path> paths(argv + 1, argv + argc);
    if (paths.empty())
      if (const char* env = std::getenv("MEANDER_BENCH_MESH")) paths.emplace_back(env);
    if (paths.empty()) {
      std::fprintf(stderr, "usage: meander_bench_peers [--benchmark_... flags] FILE... (or MEANDER_BENCH_MESH=FILE)\n");
      return 2;
    }
    for (const Path& path : paths) {
      if (path.string().starts_with("-")) {
        std::fprintf(stderr, "meander_bench_peers: unknown option %s\n", path.c_str());
        return 2;
      }
      const meander::PolygonMesh mesh = meander::read_mesh(path);
      inputs.push_back({.path = path,
                        .faces = mesh.num_faces(),
                        .triangles = int64_t(mesh.num_corners()) - 2 * int64_t(mesh.num_faces()),
                        .obj = meander::mesh_format_from_path(path) == meander::MeshFormat::obj});
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meander_bench_peers: %s\n", e.what());
    return 1;
  }

  for (const Input& input : inputs)
    for (const Loader& loader : loaders)
      if (input.obj || !loader.obj_only)
        benchmark::RegisterBenchmark(benchmark_name(loader, input).c_str(), run_load, input, loader.load)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Repetitions(5)
            ->ReportAggregatesOnly(true);
  MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  print_tables(reporter, inputs);
  benchmark::Shutdown();
  return 0;
}
