// One job layer (jobs.h, parameters.h): the CLI and the studio take the same parameters,
// under the same names, with the same ranges, and make the same files from them.
#include "test_support.h"

#include "meander/error.h"
#include "meander/io.h"
#include "meander/parameters.h"
#include "meander/shapes.h"
#include "meander/studio.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <set>

namespace meander {
namespace {

std::string dashed(std::string_view name) {
  std::string option = "--" + std::string(name);
  for (char& c : option) c = c == '_' ? '-' : c;
  return option;
}

// Every parameter of a job: its name, and a value beyond its range ("" where it has none).
template <class Job> std::vector<std::pair<std::string, std::string>> parameters_of() {
  std::vector<std::pair<std::string, std::string>> list;
  Job job;
  visit_parameters(job, [&](const Parameter& p, const auto&) {
    list.emplace_back(p.name, std::isfinite(p.max) ? std::to_string(int64_t(p.max) + 1) : "");
  });
  return list;
}

// Each of the CLI's commands offers every parameter of its job as an option, and refuses a
// value out of range naming the option, as the studio names the key.
TEST(Jobs, CliAndStudioTakeTheSameParameters) {
  const auto cases = {std::pair{"curve", parameters_of<CurveJob>()}, std::pair{"wire", parameters_of<WireJob>()},
                      std::pair{"duotone", parameters_of<DuotoneJob>()}};
  const std::string out = (test::output_dir() / "out.obj").string();
  const std::string mesh = test::write_file("cube.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                                        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n")
                             .string();
  for (const auto& [command, parameters] : cases) {
    const std::string help = test::run_cli({command, "--help"}).out;
    std::set<std::string> names;
    for (const auto& [name, beyond] : parameters) {
      SCOPED_TRACE(std::string(command) + " " + name);
      EXPECT_TRUE(names.insert(name).second) << "two parameters of one job share a name";
      EXPECT_NE(help.find(dashed(name)), std::string::npos);
      if (beyond.empty()) continue;
      const test::CommandResult r = test::run_cli({command, mesh, "-o", out, dashed(name), beyond});
      EXPECT_EQ(r.exit_code, 2);
      EXPECT_NE(r.err.find(dashed(name) + ": expected"), std::string::npos) << r.err;
      const std::string mode = command == std::string("wire") ? "variable-wire" : command;
      try {
        parse_make_request(R"({"session": "x", "mode": ")" + mode + R"(", ")" + name + R"(": )" + beyond + "}");
        ADD_FAILURE() << "the studio took " << beyond;
      } catch (const ParameterError& e) {
        EXPECT_EQ(e.parameter(), name);
        EXPECT_EQ(std::string(e.what()).rfind(name + ": expected", 0), 0u) << e.what();
      }
    }
  }
  // The studio lists the same parameters for its page's help.
  const nlohmann::json listed = nlohmann::json::parse(studio_parameters_json());
  EXPECT_EQ(listed["curve"].size(), parameters_of<CurveJob>().size());
  EXPECT_EQ(listed["wire"].size(), parameters_of<WireJob>().size() - 2); // the mode is the method and shape
  EXPECT_EQ(listed["duotone"].size(), parameters_of<DuotoneJob>().size());
  const auto samples = std::find_if(listed["curve"].begin(), listed["curve"].end(),
                                    [](const nlohmann::json& entry) { return entry["name"] == "samples"; });
  ASSERT_NE(samples, listed["curve"].end());
  EXPECT_EQ((*samples)["max"], 1000);
  EXPECT_EQ((*samples)["default"], "4");
  EXPECT_EQ(listed["curve"][0]["name"], "model_size");
  EXPECT_EQ(listed["curve"][0]["default"], "none");
  EXPECT_EQ(listed["curve"][1]["name"], "spacing");
}

// The library names a parameter it refuses; the CLI shows the name as its option.
TEST(Jobs, RefusalsNameTheParameterAndTheCliItsOption) {
  WireJob job;
  job.s = 2;
  try {
    check_parameters(job);
    ADD_FAILURE() << "s = 2 taken";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.parameter(), "s");
    EXPECT_STREQ(e.what(), "s: expected a number in [0, 1], got 2");
  }
  EXPECT_THROW(check_parameters(WireJob{.shape = WireShape::ribbon, .min_thickness = 0.4}), ParameterError);
  EXPECT_THROW(check_parameters(DuotoneJob{.subdivide = 6}), ParameterError);
  EXPECT_THROW(check_parameters(CurveJob{.curve = {.samples = 0}}), ParameterError);
  EXPECT_THROW(smooth_curves({}, {.samples = 0}), ParameterError);
  // An odd texture size passes the range and is refused by the atlas, which says which
  // parameter: the CLI names its option.
  const std::string out = (test::output_dir() / "d.glb").string();
  const std::string mesh = test::write_file("tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n").string();
  const test::CommandResult r = test::run_cli({"duotone", mesh, "-o", out, "--texture-size", "99"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("meander: --texture-size 99: expected an even number"), std::string::npos) << r.err;
}

// The same parameters make the same bytes through the CLI and through the studio.
TEST(Jobs, CliAndStudioMakeTheSameFiles) {
  const auto dir = test::output_dir();
  const std::string mesh = (dir / "pretzel.obj").string();
  ASSERT_EQ(test::run_cli({"generate", "pretzel", "--faces", "1600", "-o", mesh}).exit_code, 0);
  const StudioSurface surface = load_studio_surface("pretzel.obj", test::read_file(mesh));
  struct Case {
    std::vector<std::string> cli;
    std::string request;
    StudioFile file;
  };
  const std::vector<Case> cases = {
      {{"curve", mesh, "-o", (dir / "c.svg").string(), "--tree", "bfs", "--samples", "3"},
       R"({"session": "x", "tree": "bfs", "samples": 3})", StudioFile::svg},
      {{"wire", mesh, "-o", (dir / "c.stl").string(), "--samples", "2", "--sides", "5"},
       R"({"session": "x", "mode": "constant-wire", "samples": 2, "sides": 5})", StudioFile::stl},
      {{"wire", mesh, "-o", (dir / "v.3mf").string(), "--method", "variable", "--shape", "ribbon", "--tree", "shaped", "--levels", "1",
        "--cap-angle", "150"},
       R"({"session": "x", "mode": "variable-ribbon", "tree": "shaped", "levels": 1, "cap_angle": 150})", StudioFile::threemf},
      {{"duotone", mesh, "-o", (dir / "d.glb").string(), "--tiles", "dots", "--texture-size", "128", "--seed", "5"},
       R"({"session": "x", "mode": "duotone", "tiles": "dots", "texture_size": 128, "seed": 5})", StudioFile::glb},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.request);
    const test::CommandResult r = test::run_cli(c.cli);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const StudioResult result = make_studio_result(surface, parse_make_request(c.request).params);
    EXPECT_TRUE(studio_download(surface, result, c.file).bytes == test::read_file(c.cli[3]));
  }
}

// A variable wire follows the even mesh's flat faces, which cut below a curved input
// between their corners: drawn half sunk in the input (which a curve made with a spacing
// is moved onto), it was hidden over most of a pretzel at 6 mm of 100.
TEST(Jobs, AVariableWireIsDrawnHalfSunkInTheSurfaceItFollows) {
  const WireJob job{.curve = {.spacing = 0.3}, .method = WireMethod::variable, .levels = 1, .report = false};
  const CurveResult curve = make_curve(make_shape("pretzel", 1600), wire_curve_job(job));
  const WireResult wire = make_wire(curve, job);
  const RenderOptions options{.width = 300, .height = 200, .view = parse_view("front"), .samples = 1};
  const auto copper = [](const Image& image) {
    int64_t n = 0;
    for (size_t i = 0; i + 3 < image.rgba.size(); i += 4) n += image.rgba[i] > image.rgba[i + 2] + 40;
    return n;
  };
  Scene alone;
  alone.meshes.push_back({.mesh = wire.mesh, .color = wire_color});
  // Alone, the wire's back shows between its front passes; sunk, only its front half.
  const int64_t all = copper(render(alone, options)), shown = copper(render(wire_scene(wire.mesh, curve, job), options));
  EXPECT_GT(shown, all / 3) << shown << " of " << all << " pixels";
  EXPECT_LT(shown, all);
}

} // namespace
} // namespace meander
