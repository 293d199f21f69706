// The adversarial corpus (tests/corpus/): malformed and awkward files, each given to
// `meander curve` as a user would, with the outcome tests/corpus/EXPECTED states for it:
// the exit code and the exact lines on stderr (the refusal naming the file and position,
// or the repairs made). A refused file leaves no output; an accepted one leaves a curve
// whose cycle the independent checker (certificate.h) certifies.
// Every file of the folder must have an entry, and every entry a file.
#include "certificate.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

namespace meander {
namespace {

const std::filesystem::path corpus = MEANDER_TEST_CORPUS;

struct Expected {
  int exit_code = 0;
  std::string err; // with $IN for the input's path
};

// EXPECTED: "== FILE EXIT" lines, each followed by the stderr lines expected ($IN stands
// for the input's path); '#' lines and empty lines are comments.
std::map<std::string, Expected> read_expected() {
  std::ifstream in(corpus / "EXPECTED");
  std::map<std::string, Expected> expected;
  Expected* current = nullptr;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line.starts_with("#")) continue;
    if (line.starts_with("== ")) {
      const size_t space = line.rfind(' ');
      current = &expected[line.substr(3, space - 3)];
      current->exit_code = std::stoi(line.substr(space + 1));
    } else if (current) {
      current->err += line + "\n";
    }
  }
  return expected;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

TEST(Corpus, EveryFileHasAnExpectedOutcomeAndTheyAreMany) {
  const auto expected = read_expected();
  std::set<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(corpus))
    if (entry.path().filename() != "EXPECTED") files.insert(entry.path().filename().string());
  std::set<std::string> listed;
  for (const auto& [file, outcome] : expected) listed.insert(file);
  EXPECT_EQ(files, listed);
  EXPECT_GE(files.size(), 60u);
}

class CorpusFile : public ::testing::TestWithParam<std::string> {};

TEST_P(CorpusFile, HasItsExpectedOutcome) {
  const Expected expected = read_expected().at(GetParam());
  const std::string input = (corpus / GetParam()).string();
  const std::filesystem::path dir = test::output_dir(), output = dir / "curve.obj";
  const test::CommandResult result = test::run_cli({"curve", input, "-o", output.string()});
  EXPECT_EQ(result.exit_code, expected.exit_code);
  EXPECT_EQ(result.err, replace_all(expected.err, "$IN", input));
  EXPECT_EQ(std::filesystem::exists(output), result.exit_code == 0);
  if (result.exit_code != 0) return;
  // The curve of an accepted file, and its cycle's certificate, as the independent
  // checker reads them (certificate.h): every triangle once, neighbours sharing an edge,
  // no edge between two cycles, a closed curve per cycle on its triangles.
  const std::filesystem::path triangles = dir / "cycle.obj";
  const test::CommandResult certified = test::run_cli({"curve", input, "-o", output.string(), "--triangles", triangles.string()});
  ASSERT_EQ(certified.exit_code, 0) << certified.err;
  const test::ObjGroups certificate = test::parse_obj_groups(triangles), curve = test::parse_obj_groups(output);
  const test::CertificateFacts facts = test::check_certificate(certificate);
  EXPECT_EQ(facts.problem, "");
  EXPECT_GE(facts.cycles, 1);
  ASSERT_EQ(int(curve.lines.size()), facts.cycles);
  for (const auto& l : curve.lines) EXPECT_TRUE(l.size() >= 3 && l.front() == l.back()) << "each curve is a closed l element";
  EXPECT_LT(test::curve_distance_ratio(curve, certificate), 0.25);
}

std::vector<std::string> corpus_files() {
  std::vector<std::string> files;
  for (const auto& [file, outcome] : read_expected()) files.push_back(file);
  return files;
}

INSTANTIATE_TEST_SUITE_P(Corpus, CorpusFile, ::testing::ValuesIn(corpus_files()),
                         [](const auto& p) { return test::test_name(p.param); });

} // namespace
} // namespace meander
