// meander_bench_stages FILE [--runs N]: runs the pipeline of `meander curve FILE -o OUT.ply`
// (read, check, then make_curve's stages, then write) N times in one process and prints,
// as a markdown table, the median wall-clock time of each stage and the peak resident
// memory, in MB and in bytes per input triangle.
#include "meander/check.h"
#include "meander/io.h"
#include "meander/pipeline.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct Pass {
  meander::StageTimes times; // the stages in the order they ran, then "total"
  int64_t input_triangles = 0;
  int64_t curve_points = 0;
  std::vector<std::string> repairs;
};

// The seconds since `start`, moving `start` to now.
double lap(Clock::time_point& start) {
  const Clock::time_point now = Clock::now();
  const double seconds = std::chrono::duration<double>(now - start).count();
  start = now;
  return seconds;
}

// A polygon of n sides counts as the n - 2 triangles of a fan, so that bytes per triangle
// compare across triangle and polygon meshes.
int64_t triangle_count(const meander::PolygonMesh& mesh) {
  return int64_t(mesh.num_corners()) - 2 * int64_t(mesh.num_faces());
}

Pass run_pass(const std::filesystem::path& input, const std::filesystem::path& output) {
  Pass pass;
  const Clock::time_point begin = Clock::now();
  Clock::time_point start = begin;
  meander::PolygonMesh mesh = meander::read_mesh(input);
  pass.times.emplace_back("read", lap(start));
  pass.input_triangles = triangle_count(mesh);
  meander::RepairResult repaired = meander::repair(std::move(mesh), input.string());
  pass.times.emplace_back("check", lap(start));
  pass.repairs = std::move(repaired.repairs);
  const meander::CurveResult result =
      meander::make_curve(std::move(repaired.mesh), std::move(repaired.connectivity), {}, &pass.times);
  start = Clock::now();
  meander::write_polylines(result.curves, output);
  pass.times.emplace_back("write", lap(start));
  pass.times.emplace_back("total", std::chrono::duration<double>(Clock::now() - begin).count());
  pass.curve_points = int64_t(result.curves.points.size());
  return pass;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

double peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024; // Linux reports kilobytes
}

int usage(const char* message) {
  std::fprintf(stderr, "meander_bench_stages: %s\nusage: meander_bench_stages FILE [--runs N]\n", message);
  return 2;
}

} // namespace

int main(int argc, char** argv) {
  std::filesystem::path input;
  int runs = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::atoi(argv[++i]);
      if (runs < 1) return usage("--runs needs a positive number");
    } else if (input.empty() && !arg.starts_with("-")) {
      input = arg;
    } else {
      return usage(("unexpected argument '" + std::string(arg) + "'").c_str());
    }
  }
  if (input.empty()) return usage("no input file");

  const std::filesystem::path output =
      std::filesystem::temp_directory_path() / ("meander_bench_curve_" + std::to_string(getpid()) + ".ply");
  std::vector<Pass> passes;
  try {
    for (int r = 0; r < runs; ++r) {
      passes.push_back(run_pass(input, output));
      // Otherwise the next write would pay for freeing this curve's blocks as it replaces it.
      std::filesystem::remove(output);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meander_bench_stages: %s\n", e.what());
    return 1;
  }

  const Pass& first = passes.front();
  for (const std::string& line : first.repairs) std::fprintf(stderr, "%s: repaired: %s\n", input.c_str(), line.c_str());
  std::printf("%s: %lld input triangles, curve of %lld points; median of %d runs\n\n", input.filename().c_str(),
              (long long)first.input_triangles, (long long)first.curve_points, runs);
  std::printf("| stage | ms |\n|---|---:|\n");
  for (size_t s = 0; s < first.times.size(); ++s) {
    std::vector<double> seconds;
    for (const Pass& p : passes) seconds.push_back(p.times[s].second);
    std::printf("| %s | %.1f |\n", first.times[s].first.c_str(), median(seconds) * 1e3);
  }
  const double peak = peak_rss_bytes();
  std::printf("\npeak RSS %.1f MB = %.0f bytes per input triangle\n", peak / 1e6,
              peak / double(std::max<int64_t>(first.input_triangles, 1)));
  return 0;
}
