// Small helpers the subcommands share.
#pragma once

#include "meander/check.h"
#include "meander/error.h"
#include "meander/parameters.h"
#include "meander/pipeline.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>

namespace meander::cli {

// Checks before any work is done that `path` has one of the extensions and that its
// folder exists, so a long run does not end in a refusal. Throws UsageError / IOError.
void require_output_path(const std::filesystem::path& path, std::initializer_list<std::string_view> extensions,
                         std::string_view option);

// The path's extension in lower case (".svg").
std::string lowercase_extension(const std::filesystem::path& path);

// The option of a parameter (parameters.h): "--texture-size" for texture_size.
std::string option_name(std::string_view parameter);

// Adds an option for each parameter of a CurveJob, WireJob or DuotoneJob, bound to the
// job's field: its name as option_name gives it, its help, its default (the job's value
// now) and its choices. A value is read by set_parameter, whose refusal names the option.
template <class Job> void add_parameters(CLI::App& app, Job& job);

// --max-faces: refuse larger inputs (RepairOptions::max_faces).
void add_max_faces(CLI::App& app, int64_t& max_faces);
// What -v says of the cycle's tree (made with CycleOptions::count_leaves).
std::string leaves_note(int64_t leaves);

// Refuses (UsageError, before any work) a --spacing whose remeshed surface would not fit in
// memory, naming its faces.
void require_memory_for_spacing(const std::string& input, const PolygonMesh& mesh, std::optional<double> model_size,
                                std::optional<double> spacing, Quadrangulation quadrangulation);

// Whether the input may be put in another order before `job` (RepairOptions::reorder):
// not under --quad none, which refuses a face that is not a quad by its number.
bool reorders(const CurveJob& job);

// Refuses (UsageError, naming `input`), before it is made, a result of this many
// elements at this many bytes each that would not fit in the machine's memory: the
// kernel would kill the process minutes later instead, with nothing said. `what` names
// the result ("the variable wire would have 766464000 triangles"), `advice` what to
// change; either is called only when refusing.
void require_memory(const std::string& input, double elements, double bytes_each,
                    const std::function<std::string()>& what, const std::function<std::string(double memory)>& advice);

// Reads a mesh and repairs it (each repair reported on stderr as "NAME: repaired: ...",
// each notice as "NAME: note: ..."), or refuses it under strict. Adds the read and check
// times to the log when verbose. `options.strict`, `max_faces` and `reorder` as in
// RepairOptions.
class StageLog;
RepairResult read_and_repair(const std::filesystem::path& path, StageLog& log, const RepairOptions& options);

// The curve of the mesh read from `input`: read and repaired as read_and_repair does
// (`strict` as RepairOptions::strict, the input's faces limited to job.max_faces), refused
// before any work where its spacing would not fit in memory, then make_curve, each stage's
// time in the log.
CurveResult make_input_curve(const std::string& input, StageLog& log, const CurveJob& job, bool strict);

// Runs work() on the mesh read from `input`. The library's topology refusals (a quad
// mesh with boundary, a triangle under --quad none, ...) do not know the file; the
// user should still read which one, as in the readers' messages.
template <class F> auto about_input(const std::string& input, F&& work) -> decltype(work()) {
  try {
    return work();
  } catch (const TopologyError& e) {
    throw TopologyError(input + ": " + e.what());
  }
}

// Prints "  stage    12.3 ms" lines on stderr when verbose.
class StageLog {
public:
  explicit StageLog(bool verbose) : verbose_(verbose), start_(std::chrono::steady_clock::now()) {}
  void lap(std::string_view stage);
  void restart() { start_ = std::chrono::steady_clock::now(); }
  void add(std::string_view stage, double seconds);
  void note(const std::string& line);
  bool verbose() const { return verbose_; }

private:
  bool verbose_;
  std::chrono::steady_clock::time_point start_;
};

} // namespace meander::cli
