// --model-size and lengths with units: the model scaled to a physical size, every file
// in millimetres (glTF in metres), units refused without a model size.
#include "meander/error.h"
#include "meander/evenness.h"
#include "meander/io.h"
#include "meander/parameters.h"
#include "meander/pipeline.h"
#include "meander/shapes.h"
#include "meander/studio.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>

namespace meander {
namespace {

TEST(ModelSize, LengthsReadTheirUnitsInMillimetres) {
  std::optional<double> spacing;
  const struct {
    const char* text;
    double millimetres;
  } cases[] = {{"3", 3}, {"3mm", 3}, {"0.3cm", 3}, {"1in", 25.4}, {"0.002m", 2}, {"1e1mm", 10}};
  for (const auto& c : cases) {
    set_parameter(parameters::spacing, c.text, spacing);
    EXPECT_DOUBLE_EQ(*spacing, c.millimetres) << c.text;
  }
  double thickness = 0;
  set_parameter(parameters::thickness, "1.5mm", thickness);
  EXPECT_DOUBLE_EQ(thickness, 1.5);
  std::optional<double> radius = 1.0;
  set_parameter(parameters::radius, "auto", radius);
  EXPECT_FALSE(radius);
  set_parameter(parameters::model_size, "12cm", spacing);
  EXPECT_DOUBLE_EQ(*spacing, 120);
  for (const char* bad : {"3furlong", "mm", "3 mm", "-3mm", "0mm"}) {
    try {
      set_parameter(parameters::spacing, bad, spacing);
      ADD_FAILURE() << bad;
    } catch (const ParameterError& e) {
      EXPECT_EQ(e.parameter(), "spacing");
    }
  }
  // A parameter that is not a length takes no unit.
  int samples = 0;
  EXPECT_THROW(set_parameter(parameters::samples, "4mm", samples), ParameterError);
  EXPECT_TRUE(has_unit("3mm"));
  EXPECT_TRUE(has_unit("4.7in"));
  EXPECT_FALSE(has_unit("3"));
  EXPECT_FALSE(has_unit("none"));
  EXPECT_FALSE(has_unit("auto"));
}

TEST(ModelSize, ScalesTheLargestSideToTheSize) {
  const PolygonMesh mesh = torus(500); // 2.7 x 2.7 x 0.7
  const PolygonMesh sized = scaled_to_size(mesh, 100);
  EXPECT_NEAR(bounding_box(sized.positions).largest_side(), 100, 1e-3);
  EXPECT_EQ(sized.face_vertices, mesh.face_vertices);
  EXPECT_THROW(scaled_to_size(PolygonMesh{.positions = {{1, 1, 1}}}, 100), InputError);
  // The curve job scales first: its spacing is then in millimetres.
  const CurveResult curve = make_curve(mesh, CurveJob{.model_size = 100, .spacing = 4});
  const EvennessReport evenness = measure_evenness(sized, curve.curves, {.surface_samples = 1000});
  EXPECT_NEAR(evenness.gap_median, 4, 0.4);
}

class CliModelSize : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = test::output_dir();
    mesh_ = (folder_ / "pretzel.obj").string();
    write_mesh(genus_surface(2, 4000), mesh_);
  }
  std::string out(const char* name) const { return (folder_ / name).string(); }
  std::filesystem::path folder_;
  std::string mesh_;
};

TEST_F(CliModelSize, AUnitWithoutAModelSizeIsRefused) {
  for (const std::vector<std::string>& options :
       {std::vector<std::string>{"curve", "--spacing", "3mm"}, {"wire", "--spacing", "0.1", "--radius", "0.5mm"},
        {"wire", "--method", "variable", "--thickness", "1mm"}, {"duotone", "--spacing", "2cm"}}) {
    std::vector<std::string> args = options;
    args.insert(args.begin() + 1, {mesh_, "-o", out(options[0] == "duotone" ? "x.glb" : "x.obj")});
    const test::CommandResult r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("carries a unit, which needs --model-size"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out("x.obj")));
    EXPECT_FALSE(std::filesystem::exists(out("x.glb")));
  }
  const test::CommandResult unknown = test::run_cli({"curve", mesh_, "-o", out("x.obj"), "--model-size", "4furlong"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("--model-size: unknown unit 'furlong'"), std::string::npos) << unknown.err;
}

TEST_F(CliModelSize, FilesAreInMillimetresAndGltfInMetres) {
  const test::CommandResult wire = test::run_cli({"wire", mesh_, "-o", out("wire.stl"), "--model-size", "10cm", "--spacing",
                                                  "3mm", "--radius", "0.6mm"});
  ASSERT_EQ(wire.exit_code, 0) << wire.err;
  const Box3 box = bounding_box(read_mesh(out("wire.stl")).positions);
  // The pretzel's largest side is 100 mm; the wire lies on it, a radius out at most.
  EXPECT_GT(box.largest_side(), 90);
  EXPECT_LT(box.largest_side(), 101.2);
  const test::CommandResult glb = test::run_cli({"wire", mesh_, "-o", out("wire.glb"), "--model-size", "100", "--spacing",
                                                 "3", "--radius", "0.6"});
  ASSERT_EQ(glb.exit_code, 0) << glb.err;
  // The node scales the millimetres to metres; read back, the mesh is in metres.
  EXPECT_NEAR(bounding_box(read_mesh(out("wire.glb")).positions).largest_side(), box.largest_side() / 1000, 1e-4);
  const std::string bytes = test::read_file(out("wire.glb"));
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  const nlohmann::json gltf = nlohmann::json::parse(bytes.substr(20, length));
  EXPECT_EQ(gltf["nodes"][0]["scale"], nlohmann::json::array({0.001, 0.001, 0.001}));
  const test::CommandResult duotone =
      test::run_cli({"duotone", mesh_, "-o", out("duotone.glb"), "--model-size", "4in", "--regions",
                     out("a.ply") + "," + out("b.ply")});
  ASSERT_EQ(duotone.exit_code, 0) << duotone.err;
  EXPECT_NEAR(bounding_box(read_mesh(out("duotone.glb")).positions).largest_side(), 0.1016, 1e-4);
  EXPECT_NEAR(bounding_box(read_mesh(out("a.ply")).positions).largest_side(), 101.6, 0.5);
}

// A curve's SVG is its drawing from the front at true size in millimetres with a model
// size (with --spacing too, and the duotone's curve), fitted to an A4 sheet without.
TEST_F(CliModelSize, SvgIsAtTrueSizeInMillimetres) {
  auto page_width = [](const std::string& svg) {
    const size_t at = svg.find("width=\"") + 7, end = svg.find("mm\"", at);
    EXPECT_NE(end, std::string::npos) << svg.substr(0, 200);
    return std::stod(svg.substr(at, end - at));
  };
  for (const std::vector<std::string>& options :
       {std::vector<std::string>{"curve", mesh_, "-o", out("c.svg"), "--model-size", "100mm"},
        {"curve", mesh_, "-o", out("c.svg"), "--model-size", "10cm", "--spacing", "3mm"},
        {"duotone", mesh_, "-o", out("d.glb"), "--model-size", "100", "--curve", out("c.svg")}}) {
    const test::CommandResult r = test::run_cli(options);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string svg = test::read_file(out("c.svg"));
    // The pretzel's longest side, along x, is 100 mm; the curve lies on it, with a 2 mm
    // margin each side; true size at the depth of its centre, the nearer parts a little
    // larger in perspective.
    EXPECT_NEAR(page_width(svg), 104, 1);
    EXPECT_NE(svg.find("stroke-width=\"0.3\""), std::string::npos);
  }
  const test::CommandResult plain = test::run_cli({"curve", mesh_, "-o", out("c.svg")});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(page_width(test::read_file(out("c.svg"))), 210);
}

// The demo's printable wire: with a model size a wire is judged in millimetres against
// the nozzle (2 nozzles thick, a nozzle apart), its radius a fifth of the spacing; without
// one the report gives the smallest size it prints at.
TEST_F(CliModelSize, AWireIsJudgedAgainstTheNozzle) {
  const test::CommandResult sized = test::run_cli(
      {"wire", mesh_, "-o", out("wire.stl"), "--model-size", "100mm", "--spacing", "3mm", "--report", out("sized.json")});
  ASSERT_EQ(sized.exit_code, 0) << sized.err;
  EXPECT_NE(sized.err.find(": printable. Radius 0.6 (auto)"), std::string::npos) << sized.err;
  const nlohmann::json report = nlohmann::json::parse(test::read_file(out("sized.json")));
  EXPECT_TRUE(report["printable"].get<bool>());
  EXPECT_EQ(report["required_thickness"].get<double>(), 0.8);
  EXPECT_EQ(report["required_gap"].get<double>(), 0.4);
  EXPECT_GE(report["min_thickness"].get<double>(), 0.8);
  EXPECT_GE(report["min_gap"].get<double>(), 0.4);
  // A coarser nozzle than the gaps allow makes it not printable, naming the gap.
  const test::CommandResult coarse = test::run_cli({"wire", mesh_, "-o", out("wire.stl"), "--model-size", "100mm",
                                                    "--spacing", "3mm", "--nozzle", "2mm"});
  ASSERT_EQ(coarse.exit_code, 0) << coarse.err;
  EXPECT_NE(coarse.err.find("narrower than the 2 required"), std::string::npos) << coarse.err;
  EXPECT_NE(coarse.err.find(": not printable."), std::string::npos) << coarse.err;
  // Without a model size: in the model's units, with the smallest size it prints at.
  const test::CommandResult plain = test::run_cli({"wire", mesh_, "-o", out("wire.stl"), "--report", out("plain.json")});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.err.find("prints with a 0.4 mm nozzle from "), std::string::npos) << plain.err;
  EXPECT_GT(nlohmann::json::parse(test::read_file(out("plain.json")))["smallest_printable_size"].get<double>(), 0);
}

TEST(StudioModelSize, TakesLengthsWithUnitsOnlyWithASize) {
  const MakeRequest sized =
      parse_make_request(R"({"session": "x", "mode": "constant-wire", "model_size": "10cm", "spacing": "3mm", "radius": "0.5mm"})");
  EXPECT_EQ(sized.params.wire.curve.model_size, 100);
  EXPECT_EQ(sized.params.wire.curve.spacing, 3);
  EXPECT_EQ(sized.params.wire.radius, 0.5);
  try {
    parse_make_request(R"({"session": "x", "mode": "curve", "spacing": "3mm"})");
    ADD_FAILURE() << "took a unit without a size";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.parameter(), "spacing");
    EXPECT_NE(std::string(e.what()).find("needs model_size"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace meander
