#include "meander/pipeline.h"

#include "meander/connectivity.h"
#include "meander/curve_writer.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/parameters.h"
#include "meander/star_polygons.h"
#include "stages.h"

#include <optional>
#include <string>

namespace meander {

PolygonMesh scaled_to_size(PolygonMesh mesh, double size) {
  const double side = bounding_box(mesh.positions).largest_side();
  if (!(side > 0)) throw InputError("the mesh has no extent, so it has no size to scale");
  const float factor = float(size / side);
  for (Vec3& p : mesh.positions) p = p * factor;
  return mesh;
}

double spacing_edge_length(double spacing, Quadrangulation) {
  // The curve's median gap over the remeshed edge length: 0.36 (0.355 to 0.37) on closed
  // scans and generated shapes at 1/30 to 1/120 of their diagonal (docs/density.md).
  constexpr double gap_per_edge = 0.36;
  return spacing / gap_per_edge;
}

int64_t remeshed_faces(const PolygonMesh& mesh, std::optional<double> model_size, std::optional<double> spacing,
                       Quadrangulation quadrangulation) {
  if (!spacing) return 0;
  // Scaling the mesh by k scales its area by k^2: the spacing in the mesh's units is the
  // spacing over k.
  const double side = bounding_box(mesh.positions).largest_side();
  const double k = model_size && side > 0 ? *model_size / side : 1;
  return remeshed_faces_estimate(mesh, spacing_edge_length(*spacing / k, quadrangulation));
}

PolygonMesh remesh_to_spacing(const PolygonMesh& mesh, double spacing, Quadrangulation quadrangulation, int64_t max_faces,
                              const ClosestPoints* input) {
  if (quadrangulation == Quadrangulation::none)
    throw ParameterError(parameters::spacing.name, " remeshes the surface into triangles, which quad none cannot take "
                                                   "(it needs a mesh of quads)");
  if (const double size = bounding_box(mesh.positions).largest_side(); !(spacing < size))
    throw ParameterError(parameters::spacing.name, " " + parameter_text(parameters::spacing, std::optional(spacing)) +
                                                       " is not smaller than the model (its largest side is " +
                                                       parameter_text(parameters::spacing, std::optional(size)) + ")");
  const RemeshOptions options{.edge_length = spacing_edge_length(spacing, quadrangulation), .max_faces = max_faces};
  return input ? remesh(mesh, options, *input) : remesh(mesh, options);
}

CurveResult make_curve(PolygonMesh mesh, const CurveJob& job, StageTimes* times, Progress* progress) {
  return make_curve(std::move(mesh), Connectivity(), job, times, progress);
}

EvenSurfaceOptions even_surface_options(const CurveJob& job) {
  return {.model_size = job.model_size, .spacing = job.spacing.value(), .quadrangulation = job.quadrangulation, .max_faces = job.max_faces};
}

EvenSurface make_even_surface(PolygonMesh mesh, const EvenSurfaceOptions& options) {
  if (options.model_size) mesh = scaled_to_size(std::move(mesh), *options.model_size);
  ClosestPoints on_input(mesh);
  PolygonMesh even = remesh_to_spacing(mesh, options.spacing, options.quadrangulation, options.max_faces, &on_input);
  return {options, std::move(mesh), std::move(on_input), std::move(even)};
}

namespace {

// make_curve's stages after the remesh, on `mesh`: the input's own, or with `even` its
// remeshed surface, the curve then moved onto even->input.
CurveResult curve_on(PolygonMesh mesh, Connectivity connectivity, const CurveJob& job, const EvenSurface* even, Stages& stages,
                     Progress* progress) {
  CurveResult result;
  if (job.slab_mesh) {
    stages.begin("slab mesh");
    if (job.slab_mesh->star_sides > 0) {
      StarredPolygons starred = star_polygons(std::move(mesh), job.slab_mesh->star_sides);
      mesh = std::move(starred.mesh);
      result.stars = starred.stars;
    }
    if (job.slab_mesh->caps) {
      CapFlips flipped = flip_caps(std::move(mesh), *job.slab_mesh->caps);
      mesh = std::move(flipped.mesh);
      result.cap_flips = flipped.flips;
      result.cap_cuts = flipped.cuts;
    }
    if (job.slab_mesh->needles) {
      NeedleCollapses collapsed = collapse_needles(std::move(mesh), *job.slab_mesh->needles);
      mesh = std::move(collapsed.mesh);
      result.needle_collapses = collapsed.collapses;
    }
    // Flips keep the sizes, which the check below would not catch.
    if (result.stars + result.cap_flips + result.cap_cuts + result.needle_collapses > 0) connectivity = Connectivity();
  }
  if (connectivity.halfedge_edge.size() != mesh.face_vertices.size() || connectivity.edge_start.empty()) {
    stages.begin("connectivity");
    connectivity = build_connectivity(mesh);
  }
  stages.begin("quadrangulate");
  switch (job.quadrangulation) {
  case Quadrangulation::dual_simplest: result.quads = dual_simplest(std::move(mesh), std::move(connectivity)); break;
  case Quadrangulation::catmull_clark: result.quads = catmull_clark_quads(mesh, connectivity); break;
  case Quadrangulation::none: result.quads = quads_as_is(mesh, connectivity); break;
  }
  mesh = PolygonMesh();
  connectivity = Connectivity();
  if (job.quadrangulation != Quadrangulation::dual_simplest) {
    if (const int32_t open = count_open_sides(result.quads); open > 0)
      throw TopologyError("the mesh has boundary (" + std::to_string(open) +
                          " open quad sides): quad catmull-clark and quad none need a closed mesh, because "
                          "Taubin's cycle is only defined there; the default quad dual-simplest handles "
                          "boundaries");
  }
  stages.begin("cycle");
  // A remeshed curve is moved onto the input surface before it is written, so it is sampled whole.
  const bool sample = job.sample || even;
  std::optional<CycleCurveWriter> writer;
  if (!sample && !job.output.empty()) writer.emplace(result.quads, job.curve, job.output);
  result.cycle = hamiltonian_cycle(result.quads, job.cycle, writer ? writer->observer() : nullptr);
  if (writer) {
    stages.begin("smooth + write");
    result.points_written = writer->finish(result.cycle);
  }
  if (sample) {
    stages.begin("smooth");
    result.curves = cycle_curves(result.quads, result.cycle, job.curve);
    if (even) {
      stages.begin(job.relax > 0 ? "relax" : "project");
      if (job.relax > 0) {
        RelaxedCurves relaxed =
            relax_curves(result.curves, even->input, even->on_input, {.spacing = *job.spacing, .iterations = job.relax}, progress);
        result.curves = std::move(relaxed.curves);
        result.normals = std::move(relaxed.normals);
      } else {
        result.normals.resize(result.curves.points.size());
        even->on_input.project(result.curves.points, result.normals);
      }
    }
    if (!job.output.empty()) {
      stages.begin("write curve");
      write_polylines(result.curves, job.output);
      result.points_written = int64_t(result.curves.points.size());
    }
  }
  stages.end();
  return result;
}

} // namespace

CurveResult make_curve(PolygonMesh mesh, Connectivity connectivity, const CurveJob& job, StageTimes* times,
                       Progress* progress) {
  Stages stages(times, progress);
  if (!job.spacing) {
    if (job.model_size) mesh = scaled_to_size(std::move(mesh), *job.model_size);
    return curve_on(std::move(mesh), std::move(connectivity), job, nullptr, stages, progress);
  }
  stages.begin("remesh");
  EvenSurface even = make_even_surface(std::move(mesh), even_surface_options(job));
  CurveResult result = curve_on(std::move(even.even), Connectivity(), job, &even, stages, progress);
  result.surface = std::move(even.input);
  return result;
}

CurveResult make_curve(const EvenSurface& even, const CurveJob& job, StageTimes* times, Progress* progress) {
  if (!job.spacing || !(even.options == even_surface_options(job)))
    throw UsageError("make_curve: the even surface was made for another spacing, model size, quadrangulation or face limit");
  Stages stages(times, progress);
  CurveResult result = curve_on(even.even, Connectivity(), job, &even, stages, progress);
  result.surface = even.input;
  return result;
}

} // namespace meander
