// Helpers shared by the test files: where the real meshes are, a fresh output folder
// per test, and running the CLI as a user would.
#pragma once

#include "meander/mesh.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <optional>
#include <utility>
#include <string>
#include <string_view>
#include <vector>

namespace meander::test {

// ../shared/meshes (set by CMake); tests that need it skip when it is absent.
std::filesystem::path shared_meshes();

// Both meshes in one, b's vertices moved by `shift`: a mesh of several components.
PolygonMesh side_by_side(PolygonMesh a, const PolygonMesh& b, Vec3 shift);

// The angles of triangle f at its three corners, in degrees.
std::array<double, 3> triangle_angles_degrees(const PolygonMesh& mesh, int32_t f);

// The faces of `mesh` whose corners all lie within `radius` of `centre`, with the
// vertices they use: a small piece of a large mesh, where something happens, for a test.
PolygonMesh crop(const PolygonMesh& mesh, Vec3 centre, double radius);

// Whether the environment variable CI is set (as in CI runs): a dependency a test needs
// and does not find is then a failure, not a skip, so that the suite cannot pass by
// skipping.
bool in_ci();

// Skips the test (fails it under CI) with `reason` unless `found`.
#define MEANDER_REQUIRE(found, reason)                                                                  \
  do {                                                                                                  \
    if (!(found)) {                                                                                     \
      if (::meander::test::in_ci()) GTEST_FAIL() << (reason) << " (CI is set: missing is a failure)"; \
      GTEST_SKIP() << (reason);                                                                        \
    }                                                                                                   \
  } while (0)

// Empty when shared_meshes() is a folder, else why the tests that need it cannot run.
std::string shared_meshes_missing();

#define MEANDER_REQUIRE_SHARED_MESHES()                                                                 \
  MEANDER_REQUIRE(::meander::test::shared_meshes_missing().empty(), ::meander::test::shared_meshes_missing())

// An empty folder for the current test: build/tests/output/<Suite>.<Test>/.
std::filesystem::path output_dir();

// Writes `text` to a file in the current test's folder (without emptying it, unlike
// output_dir()) and returns its path.
std::filesystem::path write_file(std::string_view name, std::string_view text);

// The whole file as bytes ("" if it cannot be read).
std::string read_file(const std::filesystem::path& path);

// A GoogleTest parameter name made from a file name: "bunny_closed.off" -> "bunny_closed_off".
std::string test_name(std::string_view file);

struct CommandResult {
  int exit_code = -1; // 128 + the signal's number where a signal ended it

  std::string out;
  std::string err;
};

// Runs the meander CLI with the given arguments (no shell: each argument as is). With
// `max_file_size`, no file it writes may grow past that many bytes: the kernel ends it
// with SIGXFSZ at the write or reservation that would (RLIMIT_FSIZE), a kill at a point
// that does not depend on timing.
CommandResult run_cli(const std::vector<std::string>& args, std::optional<uint64_t> max_file_size = std::nullopt);

// Runs a shell command line (another program: a slicer, a validator) and returns its exit
// status (as pclose gives it) and what it printed on its standard output and error.
std::pair<int, std::string> run_program(const std::string& command);

// `prusa-slicer --info FILE` (Debian's prusa-slicer, which `make test` installs) as a
// judge of a printable file: whether it says "manifold = yes" and the number of parts it
// counts ("number_of_parts"), -1 if it printed none; MEANDER_REQUIRE it first
// (prusa_slicer_found).
bool prusa_slicer_found();
struct SlicerInfo {
  int status = -1;
  bool manifold = false;
  int parts = -1;
  int objects = 0; // blocks of sizes it printed: one per object
  std::string text;
};
SlicerInfo prusa_slicer_info(const std::filesystem::path& file);

// A path of an SVG as Meander writes it ("M x y L x y ... [Z]"), read by the test's own
// parser; `layer` counts the Inkscape layers before it, less one.
struct SvgPath {
  std::vector<std::array<double, 2>> points;
  bool closed = false;
  int layer = -1;
};
std::vector<SvgPath> read_svg_paths(const std::string& svg, int& layers);

} // namespace meander::test
