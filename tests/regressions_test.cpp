// Every input a fuzzer ever failed on (tests/regressions/TARGET/FILE, TARGET one of
// fuzz/CMakeLists.txt's targets) replayed through that target's own body: Meander
// refuses it with its own error or handles it, keeping the invariants the target
// checks. Under `make test-sanitize` the sanitizers watch the replay too.
#include "fuzz_targets.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <map>

namespace meander {
namespace {

namespace fs = std::filesystem;

using Target = std::function<std::string(std::span<const uint8_t>)>;

const std::map<std::string, Target>& targets() {
  static const std::map<std::string, Target> all = {
      {"fuzz_read_obj", [](auto b) { return fuzz::read_mesh_target(b, MeshFormat::obj); }},
      {"fuzz_read_ply", [](auto b) { return fuzz::read_mesh_target(b, MeshFormat::ply); }},
      {"fuzz_read_stl", [](auto b) { return fuzz::read_mesh_target(b, MeshFormat::stl); }},
      {"fuzz_read_off", [](auto b) { return fuzz::read_mesh_target(b, MeshFormat::off); }},
      {"fuzz_read_gltf", [](auto b) { return fuzz::read_mesh_target(b, MeshFormat::gltf); }},
      {"fuzz_repair", fuzz::repair_target},
      {"fuzz_curve", fuzz::curve_target},
      {"fuzz_wire", fuzz::wire_target},
      {"fuzz_duotone", fuzz::duotone_target},
      {"fuzz_textured_obj", fuzz::textured_obj_target},
      {"fuzz_image", fuzz::image_target},
      {"fuzz_studio_request", fuzz::make_request_target},
      {"fuzz_studio_upload", fuzz::upload_target},
      {"fuzz_studio_http", fuzz::http_target},
  };
  return all;
}

// "fuzz_read_obj/crash-1234": every regression file, by folder.
std::vector<std::string> regression_files() {
  std::vector<std::string> files;
  for (const auto& folder : fs::directory_iterator(MEANDER_TEST_REGRESSIONS))
    if (folder.is_directory())
      for (const auto& file : fs::directory_iterator(folder.path()))
        files.push_back(folder.path().filename().string() + "/" + file.path().filename().string());
  std::sort(files.begin(), files.end());
  return files;
}

class Regression : public ::testing::TestWithParam<std::string> {};

TEST_P(Regression, IsHandled) {
  const std::string& file = GetParam();
  const auto target = targets().find(file.substr(0, file.find('/')));
  ASSERT_NE(target, targets().end()) << file << " is in no fuzz target's folder";
  const std::string bytes = test::read_file(fs::path(MEANDER_TEST_REGRESSIONS) / file);
  EXPECT_EQ(target->second({reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()}), "");
}

INSTANTIATE_TEST_SUITE_P(Fuzzers, Regression, ::testing::ValuesIn(regression_files()),
                         [](const auto& p) { return test::test_name(p.param); });

} // namespace
} // namespace meander
