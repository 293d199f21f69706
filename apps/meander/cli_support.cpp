#include "cli_support.h"

#include "meander/check.h"
#include "meander/error.h"
#include "meander/io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <unistd.h>

namespace meander::cli {

std::string lowercase_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

void require_output_path(const std::filesystem::path& path, std::initializer_list<std::string_view> extensions,
                         std::string_view option) {
  const std::string ext = lowercase_extension(path);
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
    std::string list;
    for (std::string_view e : extensions) list += (list.empty() ? "" : ", ") + std::string(e);
    throw UsageError(std::string(option) + " " + path.string() + ": unsupported extension '" + ext + "' (expected " +
                     list + ")");
  }
  const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  if (!std::filesystem::is_directory(folder))
    throw IOError(path.string() + ": cannot write: folder '" + folder.string() + "' does not exist");
}

std::string option_name(std::string_view parameter) {
  std::string name = "--" + std::string(parameter);
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

template <class Job> void add_parameters(CLI::App& app, Job& job) {
  visit_parameters(job, [&app](const Parameter& p, auto& value) {
    using T = std::decay_t<decltype(value)>;
    const std::string name = option_name(p.name);
    std::string help(p.help);
    if (std::isfinite(p.max)) help += " (" + parameter_text(p, p.min) + ".." + parameter_text(p, p.max) + ")";
    else if (std::isfinite(p.min)) help += " (>= " + parameter_text(p, p.min) + ")";
    if constexpr (std::is_same_v<T, bool>) {
      app.add_flag(name, value, help);
      return;
    }
    CLI::Option* option = app.add_option_function<std::string>(
        name,
        [&app, &p, &value](const std::string& text) {
          const std::string model_size = option_name(parameters::model_size.name);
          const CLI::Option* sized = app.get_option_no_throw(model_size);
          check_unit(p, text, sized && sized->count() > 0, model_size);
          set_parameter(p, text, value);
        },
        help);
    option->default_str(parameter_text(p, value));
    std::string type;
    if constexpr (std::is_enum_v<T>) {
      for (std::string_view choice : p.choices) type += (type.empty() ? "{" : ",") + std::string(choice);
      type += "}";
    } else if constexpr (std::is_arithmetic_v<T>) {
      type = std::is_integral_v<T> ? "INT" : "FLOAT";
    } else {
      type = p.choices.empty() ? "TEXT" : "FLOAT|" + std::string(p.choices[0]); // radius, spacing: a number or a word
    }
    option->type_name(type);
  });
}

template void add_parameters(CLI::App&, CurveJob&);
template void add_parameters(CLI::App&, WireJob&);
template void add_parameters(CLI::App&, DuotoneJob&);
template void add_parameters(CLI::App&, ImageJob&);

void add_max_faces(CLI::App& app, int64_t& max_faces) {
  app.add_option("--max-faces", max_faces, "refuse an input, or a surface remeshed to --spacing, of more faces (0: no limit)")->check(CLI::NonNegativeNumber)->capture_default_str();
}

std::string leaves_note(int64_t leaves) {
  return "tree: " + std::to_string(leaves) + " leaves (the tips of the curve's branches; --branches sets how many)";
}

void require_memory_for_spacing(const std::string& input, const PolygonMesh& mesh, std::optional<double> model_size,
                                std::optional<double> spacing, Quadrangulation quadrangulation) {
  // Remeshing, relaxing (with its pocket samples) and making the curve took about 3.8 KB
  // per estimated remeshed face at their peak, above the input's own memory (the kitten
  // at 1/270 and 1/530 of its diagonal: 150 and 428 MB for 29k and 112k faces, GNU
  // time's maximum RSS).
  constexpr double kBytesPerRemeshedFace = 4000;
  const int64_t faces = remeshed_faces(mesh, model_size, spacing, quadrangulation);
  require_memory(
      input, double(faces), kBytesPerRemeshedFace,
      [&] {
        return "the surface remeshed to --spacing " + parameter_text(parameters::spacing, spacing) + " would have about " +
               std::to_string(faces) + " faces";
      },
      [](double) -> std::string { return "choose a larger --spacing"; });
}

bool reorders(const CurveJob& job) { return job.quadrangulation != Quadrangulation::none; }

void StageLog::lap(std::string_view stage) {
  const auto now = std::chrono::steady_clock::now();
  add(stage, std::chrono::duration<double>(now - start_).count());
  start_ = now;
}

void StageLog::add(std::string_view stage, double seconds) {
  if (verbose_) std::fprintf(stderr, "  %-14.*s %9.1f ms\n", int(stage.size()), stage.data(), seconds * 1e3);
}

void StageLog::note(const std::string& line) {
  if (verbose_) std::fprintf(stderr, "%s\n", line.c_str());
}

void require_memory(const std::string& input, double elements, double bytes_each,
                    const std::function<std::string()>& what, const std::function<std::string(double memory)>& advice) {
  const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (!(memory > 0) || elements * bytes_each <= memory) return;
  const auto gib = [](double bytes) { return std::to_string(int64_t(std::ceil(bytes / double(1 << 30)))) + " GiB"; };
  throw UsageError(input + ": " + what() + " and need about " + gib(elements * bytes_each) + " of memory, and this machine has " +
                   gib(memory) + ": " + advice(memory));
}

RepairResult read_and_repair(const std::filesystem::path& path, StageLog& log, const RepairOptions& options) {
  PolygonMesh mesh = read_mesh(path);
  log.lap("read");
  RepairResult repaired = repair(std::move(mesh), path.string(), options);
  for (const std::string& line : repaired.repairs) std::fprintf(stderr, "%s: repaired: %s\n", path.string().c_str(), line.c_str());
  for (const std::string& line : repaired.notices) std::fprintf(stderr, "%s: note: %s\n", path.string().c_str(), line.c_str());
  log.lap("check");
  if (repaired.reordered) log.note(path.string() + ": its vertices and faces lay scattered in memory; reordered them");
  return repaired;
}

CurveResult make_input_curve(const std::string& input, StageLog& log, const CurveJob& job, bool strict) {
  RepairResult repaired = read_and_repair(input, log, {.strict = strict, .max_faces = job.max_faces, .reorder = reorders(job)});
  require_memory_for_spacing(input, repaired.mesh, job.model_size, job.spacing, job.quadrangulation);
  StageTimes times;
  CurveResult result =
      about_input(input, [&] { return make_curve(std::move(repaired.mesh), std::move(repaired.connectivity), job, &times); });
  for (const auto& [stage, seconds] : times) log.add(stage, seconds);
  log.restart();
  return result;
}

} // namespace meander::cli
