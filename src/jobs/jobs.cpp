#include "meander/jobs.h"

#include "meander/check.h"
#include "meander/closest_points.h"
#include "meander/connectivity.h"
#include "meander/error.h"
#include "meander/parameters.h"
#include "meander/solid_union.h"
#include "meander/subdivide.h"
#include "core/point_grid.h"
#include "stages.h"

#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace meander {

namespace {

ConstantWireOptions constant_options(const WireJob& job) {
  return {.shape = job.shape, .radius = job.radius, .sides = job.sides, .curve = job.curve.curve};
}

VariableWireOptions variable_options(const WireJob& job) {
  return {.shape = job.shape, .s = job.s, .t = job.t, .thickness = job.thickness, .levels = job.levels, .clear = job.clear,
          .rungs = job.rungs};
}

double covered_area(const QuadMesh& quads) {
  double area = 0;
  for (const std::array<int32_t, 4>& q : quads.quads) {
    const Vec3d a = to_double(quads.positions[size_t(q[0])]), b = to_double(quads.positions[size_t(q[1])]),
                c = to_double(quads.positions[size_t(q[2])]), d = to_double(quads.positions[size_t(q[3])]);
    area += 0.5 * (norm(cross(b - a, c - a)) + norm(cross(c - a, d - a)));
  }
  return area;
}

// Per vertex of a wire with bridges fused in: 1 within `reach` of the creases where
// they meet (the vertices the union made), where the thickness and gap rays would
// measure the crease's V.
std::vector<uint8_t> beside_creases(const SolidUnion& united, double reach) {
  std::vector<Vec3> crease;
  for (size_t v = 0; v < united.origin.size(); ++v)
    if (united.origin[v] == UnionVertex::crossing) crease.push_back(united.mesh.positions[v]);
  std::vector<uint8_t> near(united.mesh.positions.size(), 0);
  if (crease.empty()) return near;
  const PointGrid grid(crease, reach, bounding_box(united.mesh.positions));
  for (size_t v = 0; v < near.size(); ++v)
    grid.for_each_near(united.mesh.positions[v], [&](size_t rank) {
      near[v] = norm(crease[size_t(grid.ids()[rank])] - united.mesh.positions[v]) <= reach;
      return !near[v];
    });
  return near;
}

// Per point of a variable wire's centre line, the radius of the largest ball about it
// inside the wire (0 where the point lies outside: the slab strays from the smooth
// curve), and how far the wire reaches from it across the line (the slab's half width):
// what its bridges are sized and kept clear by.
struct SlabSize {
  std::vector<double> inscribed, extent;
  double radius = 0; // the largest extent
};
SlabSize slab_size(const PolygonMesh& wire, const Polylines& centre, double spacing) {
  const size_t n = centre.points.size();
  SlabSize size{.inscribed = std::vector<double>(n), .extent = std::vector<double>(n)};
  const std::vector<uint8_t> inside = inside_solid(wire, centre.points, "wire");
  const ClosestPoints surface(wire);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i)
      if (inside[i]) size.inscribed[i] = norm(surface.closest(to_double(centre.points[i])) - to_double(centre.points[i]));
  });
  // Struts are as thick as the ball at their thinner end: none where the slab is less
  // than a quarter of its usual thickness about the line (the line runs near its face;
  // half left long stretches of a bunny's thin parts untied).
  std::vector<double> balls;
  for (const double b : size.inscribed)
    if (b > 0) balls.push_back(b);
  if (!balls.empty()) {
    std::nth_element(balls.begin(), balls.begin() + ptrdiff_t(balls.size() / 2), balls.end());
    const double thinnest = 0.25 * balls[balls.size() / 2];
    for (double& b : size.inscribed)
      if (b < thinnest) b = 0;
  }
  // Each vertex of the wire counts for the nearest point of the line (its own pass's,
  // within a spacing); then each point takes the most of itself and the two points on
  // either side.
  const PointGrid lines(centre.points, spacing, bounding_box(wire.positions));
  std::vector<int32_t> nearest(wire.positions.size(), -1);
  std::vector<double> distance(wire.positions.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nearest.size(), 4096), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t v = range.begin(); v < range.end(); ++v)
      distance[v] = std::sqrt(lines.nearest_squared(wire.positions[v], spacing, [&](int32_t id, double) {
        nearest[v] = id;
        return true;
      }));
  });
  std::vector<double> own(n, 0);
  for (size_t v = 0; v < nearest.size(); ++v)
    if (distance[v] < INFINITY) own[size_t(nearest[v])] = std::max(own[size_t(nearest[v])], distance[v]);
  for (int32_t c = 0; c < centre.size(); ++c) {
    const int32_t begin = centre.start[size_t(c)], count = centre.start[size_t(c) + 1] - begin;
    for (int32_t k = 0; k < count; ++k)
      for (int32_t d = -2; d <= 2; ++d) {
        double& e = size.extent[size_t(begin + k)];
        e = std::max(e, own[size_t(begin + ((k + d) % count + count) % count)]);
      }
  }
  size.radius = *std::max_element(size.extent.begin(), size.extent.end());
  return size;
}

} // namespace

WireMethod parse_wire_method(std::string_view name) {
  if (name == "constant") return WireMethod::constant;
  if (name == "variable") return WireMethod::variable;
  throw UsageError("unknown wire method '" + std::string(name.substr(0, 40)) + "' (expected constant or variable)");
}

CurveJob wire_curve_job(const WireJob& job) {
  CurveJob curve = job.curve;
  if (job.method == WireMethod::variable && !job.keep_faces) {
    curve.slab_mesh = SlabMeshOptions{};
    if (job.cap_angle < 180) curve.slab_mesh->caps->cap_angle_degrees = job.cap_angle;
    else curve.slab_mesh->caps.reset();
  }
  return curve;
}

int64_t wire_triangles(int64_t cycle_triangles, const WireJob& job) {
  return job.method == WireMethod::constant ? constant_wire_triangles(cycle_triangles, constant_options(job))
                                            : variable_wire_triangles(cycle_triangles, variable_options(job));
}

WireResult make_wire(const CurveResult& curve, const WireJob& job, StageTimes* times, Progress* progress) {
  check_parameters(job);
  Stages stages(times, progress);
  stages.begin("wire");
  WireResult result;
  bool known_clear = false; // variable_wire searched its result already
  std::vector<uint8_t> unmeasured; // of a bridged wire: beside_creases
  if (job.method == WireMethod::constant) {
    // A curve moved onto the input surface (CurveJob::spacing) is swept where it lies, by
    // default a fifth of the spacing thick, so that neighbouring passes stay clear by
    // more than half a spacing, or less where the curve comes nearer or bends tighter
    // (a tenth less than where the tube would touch itself there).
    ConstantWireOptions options = constant_options(job);
    if (!curve.normals.empty() && !options.radius && job.curve.spacing)
      if (const double clear = max_wire_radius(curve.curves, 4); clear > 0)
        options.radius = std::min(0.2 * *job.curve.spacing, 0.9 * clear);
    ConstantWire made = curve.normals.empty() ? constant_wire(curve.quads, curve.cycle, options)
                                              : constant_wire(curve.curves, curve.normals, options);
    if (!(made.radius > 0)) throw TopologyError("the curve touches itself: no wire radius avoids a self-intersection");
    result.mesh = std::move(made.mesh);
    result.radius = made.radius;
  } else {
    VariableWire made = variable_wire(curve.quads, curve.cycle, variable_options(job), progress);
    result.mesh = std::move(made.mesh);
    known_clear = made.clear;
  }
  if (job.bridges) {
    stages.begin("bridges");
    const bool constant = job.method == WireMethod::constant;
    // The line the wire follows: the one the tube was swept along; a variable wire's
    // slabs are centred on the cycle's control points, as its smooth curve is.
    Polylines swept;
    if (!constant || curve.normals.empty()) swept = cycle_curves(curve.quads, curve.cycle, job.curve.curve);
    const Polylines& centre = !constant || curve.normals.empty() ? swept : curve.curves;
    // Passes are bridged up to 1.5 spacings apart (the spacing asked for, or the one a
    // covering curve has: the surface's area over the curve's length), or 3 radii for
    // a wire thicker than that leaves room for.
    const double spacing =
        constant && job.curve.spacing ? *job.curve.spacing : covered_area(curve.quads) / total_length(centre);
    const SlabSize slab = constant ? SlabSize{.radius = result.radius} : slab_size(result.mesh, centre, spacing);
    result.bridges = plan_bridges(centre, {.max_stretch = *job.bridges,
                                           .radius = slab.radius,
                                           .reach = std::max(1.5 * spacing, 3 * slab.radius),
                                           .inscribed = slab.inscribed,
                                           .extent = slab.extent});
    if (!result.bridges.ends.empty()) { // none where no pass is near enough: the report says so
      const PolygonMesh struts = bridge_solids(centre, result.bridges, job.sides);
      SolidUnion united;
      try {
        united = unite_solids(result.mesh, struts, "wire", "bridges");
      } catch (const InputError& e) {
        throw TopologyError(std::string(e.what()) +
                            (constant ? " at radius " + parameter_text(parameters::radius, std::optional(result.radius)) +
                                            ", so bridges cannot be fused into it: choose a smaller radius (auto: the "
                                            "largest clear one)"
                                      : ", so bridges cannot be fused into it: choose a thinner or narrower wire "
                                        "(--thickness, --s)"));
      }
      known_clear = false;
      // The ball of the thickest strut's end (a tube's radius).
      const double thickest =
          constant ? result.radius : *std::max_element(result.bridges.radii.begin(), result.bridges.radii.end()) / strut;
      unmeasured = beside_creases(united, 1.5 * thickest);
      // A face with a corner of a strut lies on the strut (a face between two points
      // of the crease, rarely, on either).
      result.bridge_faces.assign(size_t(united.mesh.num_faces()), 0);
      for (int32_t f = 0; f < united.mesh.num_faces(); ++f)
        for (const int32_t v : united.mesh.face(f)) result.bridge_faces[size_t(f)] |= united.origin[size_t(v)] == UnionVertex::second;
      result.mesh = std::move(united.mesh);
    }
  }
  if (!job.report) {
    stages.end();
    return result;
  }
  stages.begin("report");
  // In millimetres (a model size), thickness and gaps are judged against the nozzle.
  const bool millimetres = job.curve.model_size.has_value();
  const bool thickness = job.measure_thickness && job.shape == WireShape::wire;
  result.report = check_printability(
      result.mesh, {.known_clear = known_clear,
                    .thickness = thickness,
                    .required_thickness = job.min_thickness > 0 ? job.min_thickness : millimetres ? 2 * job.nozzle : 0,
                    .nozzle = thickness ? job.nozzle : 0,
                    .required_gap = millimetres && thickness ? job.nozzle : 0,
                    .unmeasured = unmeasured},
      progress);
  if (result.report.self_intersecting) result.surface_crossings = crossing_cycle_triangles(curve.quads, curve.cycle);
  stages.end();
  return result;
}

std::string wire_report_json(const WireResult& wire, const WireJob& job) {
  if (!job.bridges) return printability_json(wire.report);
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(printability_json(wire.report));
  j["bridges"] = {{"count", wire.bridges.ends.size()},
                  {"longest_stretch", wire.bridges.longest_stretch},
                  {"asked", *job.bridges},
                  {"every_pass_tied", wire.bridges.every_pass_tied},
                  {"one_piece", wire.bridges.one_piece}};
  return j.dump(2);
}

std::vector<std::string> slab_mesh_notes(const CurveResult& curve, const WireJob& job) {
  std::vector<std::string> notes;
  const auto count = [](int64_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
  char angle[32];
  std::snprintf(angle, sizeof angle, "%g", job.cap_angle);
  if (curve.stars > 0)
    notes.push_back("split " + count(curve.stars, "polygon", "polygons") + " of " + std::to_string(SlabMeshOptions{}.star_sides) +
                    " or more sides into triangles around " + (curve.stars == 1 ? "its centre" : "their centres"));
  if (curve.cap_flips > 0) notes.push_back("flipped " + count(curve.cap_flips, "edge", "edges") + " facing an angle over " + angle + " degrees");
  if (curve.cap_cuts > 0)
    notes.push_back("cut off " + count(curve.cap_cuts, "triangle", "triangles") + " with an angle over " + angle + " degrees on the boundary");
  if (curve.needle_collapses > 0) {
    std::snprintf(angle, sizeof angle, "%g", NeedleCollapseOptions{}.needle_angle_degrees);
    notes.push_back("collapsed " + count(curve.needle_collapses, "short edge", "short edges") + " of needles (an angle under " + angle +
                    " degrees) or of triangles folded over their neighbours");
  }
  return notes;
}

EvenSurfaceOptions even_surface_options(const DuotoneJob& job) {
  return {.model_size = job.model_size, .spacing = job.spacing.value(), .quadrangulation = job.duotone.quadrangulation, .max_faces = job.max_faces};
}

Duotone make_duotone(const PolygonMesh& mesh, const Connectivity& connectivity, const DuotoneJob& job, Progress* progress) {
  if (job.spacing) {
    if (progress) progress->begin("remesh");
    return make_duotone(make_even_surface(mesh, even_surface_options(job)), job, progress);
  }
  if (progress) progress->begin("duotone");
  return job.model_size ? make_duotone(scaled_to_size(mesh, *job.model_size), connectivity, job.duotone)
                        : make_duotone(mesh, connectivity, job.duotone);
}

Duotone make_duotone(const EvenSurface& even, const DuotoneJob& job, Progress* progress) {
  if (!job.spacing || !(even.options == even_surface_options(job)))
    throw UsageError("make_duotone: the even surface was made for another spacing, model size, quadrangulation or face limit");
  if (progress) progress->begin("duotone");
  return make_duotone(even.even, build_connectivity(even.even), job.duotone);
}

namespace {

// The thinnest wall a shell may have: as given, or in millimetres two nozzles of 0.4 mm
// (a wire's floor, WireJob::nozzle).
double shell_floor(const DuotoneJob& job) { return job.min_thickness > 0 ? job.min_thickness : job.model_size ? 0.8 : 0; }

} // namespace

SplitShell make_shell(const Duotone& duotone, const DuotoneJob& job) {
  if (!job.shell) throw UsageError("make_shell: the job has no shell (its wall's thickness)");
  return duotone_shell(duotone, job.tiles.style,
                       {.thickness = *job.shell, .min_thickness = shell_floor(job), .clearance = job.clearance});
}

std::string shell_summary(const SplitShell& shell, const DuotoneJob& job) {
  const auto number = [](double x) {
    std::ostringstream out;
    out << std::setprecision(6) << x;
    return out.str();
  };
  const auto at = [&](Vec3 p) { return "(" + number(p.x) + ", " + number(p.y) + ", " + number(p.z) + ")"; };
  std::string text = "2 solids, one per colour, closed and outward: " + std::to_string(shell.solids[0].num_faces()) + " and " +
                     std::to_string(shell.solids[1].num_faces()) + " triangles, ";
  // A piece in parts is printed as several: one for each of the model's parts, and with
  // a clearance more where the gap cuts off a neck of a colour region narrower than it.
  const std::array<size_t, 2> parts{inspect(shell.solids[0]).components.size(), inspect(shell.solids[1]).components.size()};
  if (parts[0] > 1 || parts[1] > 1)
    text += "in " + std::to_string(parts[0]) + " and " + std::to_string(parts[1]) + " separate parts" +
            (job.clearance > 0 ? " (the model's own, or necks of a colour narrower than the gap)" : "") + ", ";
  text += "volumes " + number(shell.volumes[0]) + " and " + number(shell.volumes[1]);
  if (job.clearance > 0)
    text += ", at least " + number(shell.apart) + " apart (at " + at(shell.apart_at) + "; clearance " + number(job.clearance) + ")";
  text += "; a wall of " + number(*job.shell);
  if (shell.sampled)
    return text + ", solid where the model is thinner than two walls (too thin or too sharply folded for a wall " +
           "that follows the quads" + (job.clearance > 0 ? ", or its quads too small for the gap" : "") +
           ": the shell was sampled, its outside within " + number(0.1 * *job.shell) + " of the surface).";
  if (shell.reduced_corners == 0) return text + " everywhere.";
  text += ", thinner at " + std::to_string(shell.reduced_corners) +
          " quad corners (the model is thinner than two walls there, or bends sharply), down to " + number(shell.thinnest) +
          " at " + at(shell.thinnest_at);
  if (shell.below_floor_corners > 0)
    text += "; thinner than the " + number(shell_floor(job)) + " a printer makes at " +
            std::to_string(shell.below_floor_corners) + " of them: not printable there";
  return text + ".";
}

std::array<ColoredPart, 2> colored_parts(const PolygonMesh& first, const PolygonMesh& second,
                                         const std::array<Color8, 2>& colors) {
  const auto name = [&](int k) {
    const Color8 c = colors[size_t(k)];
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", c[0], c[1], c[2]);
    return "colour " + std::to_string(k + 1) + " (" + hex + ")";
  };
  return {ColoredPart{first, name(0), colors[0]}, ColoredPart{second, name(1), colors[1]}};
}

TexturedMesh paint_duotone(const Duotone& duotone, const DuotoneJob& job, const Texture& atlas, StageTimes* times,
                           Progress* progress) {
  check_parameters(job);
  Stages stages(times, progress);
  stages.begin("tiles");
  TexturedMesh surface = atlas.empty() ? duotone_surface(duotone, job.tiles) : duotone_surface(duotone, job.tiles, atlas);
  if (job.subdivide > 0) {
    stages.begin("subdivide");
    surface = subdivide(surface, {.levels = job.subdivide});
  }
  stages.end();
  return surface;
}

namespace {

// The surface a curve lies on: the triangulated quad mesh it was built on (on non-planar
// polygons a fan of the input faces would cut through the curve), or the input surface
// it was moved onto (CurveJob::spacing), whose faces the projection fanned.
PolygonMesh curve_surface(const CurveResult& curve) {
  return curve.surface.num_faces() > 0 ? curve.surface : cycle_triangles(curve.quads, curve.cycle);
}

} // namespace

namespace {

DrawingOptions curve_svg_options(bool millimetres) {
  DrawingOptions options{.view = {.azimuth = 0, .elevation = 0}};
  if (millimetres) options.paper.margin = 2, options.scale = 1;
  return options;
}

} // namespace

std::string curve_svg(const Polylines& curves, const PolygonMesh& surface, bool millimetres) {
  const DrawingOptions options = curve_svg_options(millimetres);
  return drawing_svg(draw_curves(curves, surface, options), options.pen);
}

std::string curve_svg(const CurveResult& curve, bool millimetres) {
  const DrawingOptions options = curve_svg_options(millimetres);
  return drawing_svg(draw_curve(curve, options), options.pen);
}

Drawing draw_curve(const CurveResult& curve, const DrawingOptions& options) {
  return draw_curves(curve.curves, curve_surface(curve), options);
}

Scene curve_scene(const CurveResult& curve, MeshStyle occluder) {
  Scene scene;
  scene.meshes.push_back({.mesh = curve_surface(curve), .color = surface_color, .style = occluder});
  scene.curves.push_back({.curves = curve.curves});
  return scene;
}

Scene wire_scene(PolygonMesh wire, const CurveResult& curve, const WireJob& job, MeshStyle occluder,
                 std::span<const uint8_t> bridge_faces) {
  Scene scene;
  if (!bridge_faces.empty()) {
    PolygonMesh bridges = wire;
    remove_faces(wire, bridge_faces);
    std::vector<uint8_t> tube(bridge_faces.size());
    for (size_t f = 0; f < tube.size(); ++f) tube[f] = !bridge_faces[f];
    remove_faces(bridges, tube);
    scene.meshes.push_back({.mesh = std::move(bridges), .color = bridge_color});
  }
  scene.meshes.push_back({.mesh = std::move(wire), .color = wire_color});
  // A variable wire's slabs lie on the cycle's triangles, which a curve moved onto the
  // input (CurveJob::spacing) leaves: the input's surface would hide them where the even
  // mesh's flat faces cut below it.
  if (job.shape == WireShape::wire)
    scene.meshes.push_back({.mesh = job.method == WireMethod::variable ? cycle_triangles(curve.quads, curve.cycle)
                                                                       : curve_surface(curve),
                            .color = surface_color,
                            .style = occluder});
  return scene;
}

Scene duotone_scene(const TexturedMesh& surface) {
  Scene scene;
  scene.meshes.push_back({.mesh = surface.mesh, .appearance = surface.appearance});
  return scene;
}

} // namespace meander

namespace meander {

LinePicture make_line_picture(const Texture& picture, const ImageJob& job, StageTimes* times, Progress* progress) {
  check_parameters(job);
  if (picture.width < 2 || picture.height < 2)
    throw InputError("a picture of " + std::to_string(picture.width) + "x" + std::to_string(picture.height) +
                     " pixels has no tones to draw (at least 2x2)");
  Stages stages(times, progress);
  stages.begin("tones");
  LinePicture out;
  Paper paper = job.paper;
  if (job.width) {
    paper.width = *job.width + 2 * paper.margin;
    paper.height = *job.width * picture.height / picture.width + 2 * paper.margin;
  } else if ((paper.width > paper.height) != (picture.width > picture.height)) {
    std::swap(paper.width, paper.height);
  }
  const double room_x = paper.width - 2 * paper.margin, room_y = paper.height - 2 * paper.margin;
  if (!(room_x > 0 && room_y > 0))
    throw UsageError("paper of " + std::to_string(paper.width) + " x " + std::to_string(paper.height) +
                     " mm: no room inside margins of " + std::to_string(paper.margin) + " mm");
  const double scale = std::min(room_x / picture.width, room_y / picture.height);
  out.area = {.width = picture.width * scale, .height = picture.height * scale};
  out.area.x = (paper.width - out.area.width) / 2, out.area.y = (paper.height - out.area.height) / 2;
  PolygonMesh cells = tone_mesh(picture, out.area, job.tone);
  out.cells = cells.num_faces();
  stages.end();
  CurveResult curve = make_curve(std::move(cells), CurveJob{.cycle = job.cycle, .curve = job.curve}, times, progress);
  out.leaves = curve.cycle.leaves;
  out.curve = std::move(curve.curves);
  Stages layout(times, progress);
  layout.begin("layout");
  out.drawing = sheet_drawing(out.curve, paper, job.pen);
  layout.end();
  return out;
}

std::string line_picture_duotone_svg(const LinePicture& picture, const ImageJob& job) {
  const auto rgb = [](Color8 c) { return Rgb{c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f}; };
  return duotone_svg(picture.drawing, picture.area, rgb(job.colors[0]), rgb(job.colors[1]));
}

Polylines line_picture_curve(const LinePicture& picture) {
  Polylines curve = picture.curve;
  for (Vec3& p : curve.points) p.y = float(picture.drawing.paper.height - p.y);
  return curve;
}

} // namespace meander
