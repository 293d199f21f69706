// The Khronos glTF validator, run through node from tests/node_modules (`make test`
// installs it with npm ci), for the tests that write glTF.
#pragma once

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

namespace meander::test {

inline const std::filesystem::path gltf_validator_dir = std::filesystem::path(__FILE__).parent_path();

inline bool gltf_validator_installed() {
  return std::filesystem::exists(gltf_validator_dir / "node_modules/gltf-validator") &&
         std::system("node --version > /dev/null 2>&1") == 0;
}

// The validator's report on a file: {"numErrors", "numWarnings", "messages"} (see
// gltf_validate.cjs); a test failure and a discarded value if it prints anything else.
inline nlohmann::json gltf_validator_report(const std::filesystem::path& file) {
  const std::string command =
      "node '" + (gltf_validator_dir / "gltf_validate.cjs").string() + "' '" + file.string() + "' 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string out;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe.get())) out.append(buffer, n);
  const nlohmann::json report = nlohmann::json::parse(out, nullptr, false);
  if (report.is_discarded()) ADD_FAILURE() << "validator output: " << out;
  return report;
}

} // namespace meander::test
