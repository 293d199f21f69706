#include "test_support.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <tuple>
#include <numbers>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <csignal>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace meander::test {

std::filesystem::path shared_meshes() { return MEANDER_SHARED_MESHES; }

bool in_ci() { return std::getenv("CI") != nullptr; }

std::string shared_meshes_missing() {
  if (std::filesystem::is_directory(shared_meshes())) return "";
  std::string reason = "real meshes not found at ";
  reason += shared_meshes().string();
  reason += " (configure with -DMEANDER_SHARED_MESHES=...)";
  return reason;
}

namespace {

// build/tests/output/<Suite>.<Test>/, created if missing.
std::filesystem::path current_test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "unknown";
  const std::filesystem::path dir = std::filesystem::path(MEANDER_TEST_OUTPUT) / test_name(name);
  std::filesystem::create_directories(dir);
  return dir;
}

} // namespace

std::string test_name(std::string_view file) {
  std::string name(file);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

std::filesystem::path output_dir() {
  const std::filesystem::path dir = current_test_dir();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path write_file(std::string_view name, std::string_view text) {
  const std::filesystem::path path = current_test_dir() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::pair<int, std::string> run_program(const std::string& command) {
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return {-1, ""};
  char buffer[4096];
  while (const size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  return {pclose(pipe), out};
}

bool prusa_slicer_found() { return run_program("command -v prusa-slicer").first == 0; }

SlicerInfo prusa_slicer_info(const std::filesystem::path& file) {
  SlicerInfo info;
  std::tie(info.status, info.text) = run_program("prusa-slicer --info '" + file.string() + "'");
  info.manifold = info.text.find("manifold = yes") != std::string::npos;
  if (const size_t at = info.text.find("number_of_parts ="); at != std::string::npos)
    info.parts = std::atoi(info.text.c_str() + at + std::strlen("number_of_parts ="));
  for (size_t at = info.text.find("size_x"); at != std::string::npos; at = info.text.find("size_x", at + 1)) ++info.objects;
  return info;
}

CommandResult run_cli(const std::vector<std::string>& args, std::optional<uint64_t> max_file_size) {
  char out_template[] = "/tmp/meander_test_out_XXXXXX";
  char err_template[] = "/tmp/meander_test_err_XXXXXX";
  const int out_fd = mkstemp(out_template);
  const int err_fd = mkstemp(err_template);
  CommandResult result;
  // Made before fork(): the child of a threaded program calls only what is safe there.
  std::string cli = MEANDER_CLI;
  std::vector<std::string> copy = args;
  std::vector<char*> argv{cli.data()};
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out_fd, 1);
    dup2(err_fd, 2);
    if (max_file_size) {
      const rlimit size{rlim_t(*max_file_size), rlim_t(*max_file_size)}, no_core{0, 0};
      setrlimit(RLIMIT_FSIZE, &size);
      setrlimit(RLIMIT_CORE, &no_core);
      signal(SIGXFSZ, SIG_DFL);
    }
    execv(cli.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  close(out_fd);
  close(err_fd);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = read_file(out_template);
  result.err = read_file(err_template);
  std::filesystem::remove(out_template);
  std::filesystem::remove(err_template);
  return result;
}

PolygonMesh side_by_side(PolygonMesh a, const PolygonMesh& b, Vec3 shift) {
  const int32_t offset = a.num_vertices(), corners = a.num_corners();
  for (Vec3 p : b.positions) a.positions.push_back(p + shift);
  for (int32_t v : b.face_vertices) a.face_vertices.push_back(v + offset);
  for (size_t f = 1; f < b.face_start.size(); ++f) a.face_start.push_back(corners + b.face_start[f]);
  return a;
}

std::array<double, 3> triangle_angles_degrees(const PolygonMesh& mesh, int32_t f) {
  const auto v = mesh.face(f);
  std::array<double, 3> angles{};
  for (size_t k = 0; k < 3; ++k) {
    const Vec3 o = mesh.positions[size_t(v[k])], p = mesh.positions[size_t(v[(k + 1) % 3])], q = mesh.positions[size_t(v[(k + 2) % 3])];
    angles[k] = std::acos(std::clamp(dot(p - o, q - o) / (norm(p - o) * norm(q - o)), -1.0, 1.0)) * 180 / std::numbers::pi;
  }
  return angles;
}

PolygonMesh crop(const PolygonMesh& mesh, Vec3 centre, double radius) {
  PolygonMesh piece;
  std::vector<int32_t> index(mesh.positions.size(), -1);
  std::vector<int32_t> face;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto corners = mesh.face(f);
    if (!std::all_of(corners.begin(), corners.end(), [&](int32_t v) { return norm(mesh.positions[size_t(v)] - centre) < radius; }))
      continue;
    face.clear();
    for (const int32_t v : corners) {
      if (index[size_t(v)] < 0) {
        index[size_t(v)] = piece.num_vertices();
        piece.positions.push_back(mesh.positions[size_t(v)]);
      }
      face.push_back(index[size_t(v)]);
    }
    piece.add_face(face);
  }
  return piece;
}

std::vector<SvgPath> read_svg_paths(const std::string& svg, int& layers) {
  // By hand rather than std::regex, whose matching recurses per character in libstdc++
  // and overflows the stack on a path of a hundred thousand points.
  std::vector<SvgPath> paths;
  layers = 0;
  const std::string layer = "<g inkscape:groupmode=\"layer\"", path = "<path d=\"";
  for (size_t at = 0;;) {
    const size_t g = svg.find(layer, at), p = svg.find(path, at);
    if (g == std::string::npos && p == std::string::npos) break;
    if (g < p) {
      ++layers;
      at = g + layer.size();
      continue;
    }
    const size_t begin = p + path.size(), end = svg.find('"', begin);
    const std::string d = svg.substr(begin, end - begin);
    SvgPath read{.closed = d.ends_with(" Z"), .layer = layers - 1};
    std::vector<double> values;
    for (const char* c = d.c_str(); *c;) {
      if (std::isdigit(static_cast<unsigned char>(*c)) || *c == '-') values.push_back(std::strtod(c, const_cast<char**>(&c)));
      else ++c;
    }
    for (size_t i = 0; i + 1 < values.size(); i += 2) read.points.push_back({values[i], values[i + 1]});
    paths.push_back(std::move(read));
    at = end;
  }
  return paths;
}

} // namespace meander::test
