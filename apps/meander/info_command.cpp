#include "commands.h"

#include "meander/check.h"
#include "meander/error.h"
#include "meander/evenness.h"
#include "meander/io.h"
#include "meander/printability.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <optional>

namespace meander::cli {

namespace {

struct InfoArgs {
  std::string input;
  std::string curve;
  bool json = false;
  bool solid = false;
  double min_thickness = 0;
};

// --curve: the curves of a file measured on the mesh.
struct CurveEvenness {
  std::string file;
  int32_t curves = 0;
  EvennessReport report;
};

nlohmann::ordered_json evenness_json(const CurveEvenness& e) {
  const EvennessReport& r = e.report;
  return {
      {"curve", e.file},
      {"curves", e.curves},
      {"spacing_estimate", r.spacing_estimate},
      {"step", r.step},
      {"points", r.points},
      {"unpaired_points", r.unpaired},
      {"gap", {{"median", r.gap_median}, {"mean", r.gap_mean}, {"cv", r.gap_cv}, {"p5", r.gap_p5}, {"p95", r.gap_p95}}},
      {"coverage",
       {{"samples", r.surface_samples},
        {"p99", r.coverage_p99},
        {"max", r.coverage_max},
        {"farthest", {r.farthest.x, r.farthest.y, r.farthest.z}}}}};
}

// Relative to the median gap, the scale at which evenness is judged.
void print_evenness(const CurveEvenness& e) {
  const EvennessReport& r = e.report;
  const double g = r.gap_median;
  std::printf("curve                  %s: %d closed curve%s, %d points %g apart (spacing estimate %g)\n",
              e.file.c_str(), e.curves, e.curves == 1 ? "" : "s", r.points, r.step, r.spacing_estimate);
  std::printf("gap                    median %g (%.2fx the spacing estimate), CV %.2f, p5 %.2fx, p95 %.2fx median\n", g,
              g / r.spacing_estimate, r.gap_cv, r.gap_p5 / g, r.gap_p95 / g);
  if (r.unpaired > 0) std::printf("                       %d points without another pass left out\n", r.unpaired);
  std::printf("coverage               max %.2fx, p99 %.2fx median gap (%d surface points); farthest at (%g, %g, %g)\n",
              r.coverage_max / g, r.coverage_p99 / g, r.surface_samples, r.farthest.x, r.farthest.y, r.farthest.z);
}

std::string genus_text(const ComponentReport& c) {
  if (c.genus < 0) return "n/a (non-manifold)";
  return c.orientable ? std::to_string(c.genus) : std::to_string(c.genus) + " cross-cap" + (c.genus == 1 ? "" : "s");
}

void print_json(const std::string& input, const MeshReport& r, const PrintabilityReport* solid,
                const CurveEvenness* evenness) {
  nlohmann::ordered_json j;
  j["file"] = input;
  j["vertices"] = r.vertices;
  j["faces"] = r.faces;
  nlohmann::ordered_json sizes = nlohmann::ordered_json::object();
  for (const auto& [size, count] : r.faces_by_size) sizes[std::to_string(size)] = count;
  j["faces_by_size"] = sizes;
  j["edges"] = r.edges;
  j["boundary_edges"] = r.boundary_edges;
  j["boundary_loops"] = r.boundary_loops;
  j["components"] = r.components.size();
  j["orientable"] = r.orientable;
  j["non_manifold_edges"] = r.non_manifold_edges;
  j["non_manifold_vertices"] = r.non_manifold_vertices;
  j["degenerate_faces"] = r.degenerate_faces;
  j["zero_area_faces"] = r.zero_area_faces;
  j["duplicate_faces"] = r.duplicate_faces;
  j["unreferenced_vertices"] = r.unreferenced_vertices;
  j["non_finite_positions"] = r.non_finite_positions;
  j["out_of_range_indices"] = r.out_of_range_indices;
  j["misoriented_edges"] = r.misoriented_edges;
  if (!r.bounding_box.empty())
    j["bounding_box"] = {{"min", {r.bounding_box.min.x, r.bounding_box.min.y, r.bounding_box.min.z}},
                         {"max", {r.bounding_box.max.x, r.bounding_box.max.y, r.bounding_box.max.z}}};
  nlohmann::ordered_json comps = nlohmann::ordered_json::array();
  for (const ComponentReport& c : r.components)
    comps.push_back({{"faces", c.faces},
                     {"vertices", c.vertices},
                     {"edges", c.edges},
                     {"boundary_loops", c.boundary_loops},
                     {"euler_characteristic", c.euler_characteristic},
                     {"manifold", c.manifold},
                     {"orientable", c.orientable},
                     {"genus", c.genus}});
  j["component_details"] = comps;
  if (solid) j["solid"] = nlohmann::ordered_json::parse(printability_json(*solid));
  if (evenness) j["evenness"] = evenness_json(*evenness);
  std::printf("%s\n", j.dump(2).c_str());
}

void print_text(const std::string& input, const MeshReport& r, const PrintabilityReport* solid,
                const CurveEvenness* evenness) {
  std::string sizes;
  for (const auto& [size, count] : r.faces_by_size) {
    const char* name = size == 3 ? "triangles" : size == 4 ? "quads" : nullptr;
    sizes += (sizes.empty() ? "" : ", ") + std::to_string(count) + " " + (name ? name : std::to_string(size) + "-gons");
  }
  std::printf("file                   %s\n", input.c_str());
  std::printf("vertices               %d\n", r.vertices);
  std::printf("faces                  %d (%s)\n", r.faces, sizes.c_str());
  std::printf("edges                  %d\n", r.edges);
  std::printf("boundary               %d edge%s in %d loop%s\n", r.boundary_edges, r.boundary_edges == 1 ? "" : "s",
              r.boundary_loops, r.boundary_loops == 1 ? "" : "s");
  std::printf("components             %zu\n", r.components.size());
  std::printf("orientable             %s\n", r.orientable ? "yes" : "no");
  std::printf("non-manifold           %d edges, %d vertices\n", r.non_manifold_edges, r.non_manifold_vertices);
  std::printf("degenerate faces       %d (and %d with zero area)\n", r.degenerate_faces, r.zero_area_faces);
  std::printf("duplicate faces        %d\n", r.duplicate_faces);
  std::printf("unreferenced vertices  %d\n", r.unreferenced_vertices);
  std::printf("non-finite positions   %d\n", r.non_finite_positions);
  std::printf("misoriented edges      %d\n", r.misoriented_edges);
  if (!r.bounding_box.empty())
    std::printf("bounding box           (%g, %g, %g) - (%g, %g, %g)\n", r.bounding_box.min.x, r.bounding_box.min.y,
                r.bounding_box.min.z, r.bounding_box.max.x, r.bounding_box.max.y, r.bounding_box.max.z);
  for (size_t i = 0; i < r.components.size(); ++i) {
    const ComponentReport& c = r.components[i];
    std::printf("component %-4zu         %d faces, %d vertices, %d edges, %d boundary loop%s, chi %lld, %s, genus %s\n", i,
                c.faces, c.vertices, c.edges, c.boundary_loops, c.boundary_loops == 1 ? "" : "s", (long long)c.euler_characteristic,
                c.orientable ? "orientable" : "non-orientable", genus_text(c).c_str());
  }
  if (solid) std::printf("solid                  %s\n", printability_summary(*solid).c_str());
  if (evenness) print_evenness(*evenness);
}

} // namespace

Command add_info_command(CLI::App& parent) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* app = parent.add_subcommand("info", "Describe a mesh: counts, topology per component, and every problem found");
  app->add_option("IN", args->input, "input mesh (.obj .ply .stl .off .gltf .glb)")->required();
  app->add_flag("--json", args->json, "print JSON instead of text");
  CLI::Option* solid_flag = app->add_flag(
      "--solid", args->solid, "also check it as a solid to 3D-print: watertight, volume, self-intersections, minimum thickness");
  app->add_option("--min-thickness", args->min_thickness, "with --solid: the thinnest wall the printer makes, in mesh "
                                                          "units; thinner is reported as not printable")
      ->check(CLI::NonNegativeNumber)
      ->needs(solid_flag);
  app->add_option("--curve", args->curve,
                  "also measure how evenly the closed curves of this file (.obj .ply) cover the mesh: the gap "
                  "between neighbouring passes and the surface's distance to them");
  return {app, [args] {
            const PolygonMesh mesh = read_mesh(args->input);
            const MeshReport report = inspect(mesh);
            std::optional<PrintabilityReport> solid;
            if (args->solid) solid = check_printability(mesh, {.required_thickness = args->min_thickness});
            std::optional<CurveEvenness> evenness;
            if (!args->curve.empty()) {
              const Polylines curves = read_polylines(args->curve);
              // The measure does not know the file; the user should read which one.
              try {
                evenness = CurveEvenness{args->curve, curves.size(), measure_evenness(mesh, curves)};
              } catch (const InputError& e) {
                throw InputError(args->curve + ": " + e.what());
              }
            }
            if (args->json) print_json(args->input, report, solid ? &*solid : nullptr, evenness ? &*evenness : nullptr);
            else print_text(args->input, report, solid ? &*solid : nullptr, evenness ? &*evenness : nullptr);
          }};
}

} // namespace meander::cli
