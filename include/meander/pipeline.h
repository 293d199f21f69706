// The whole curve pipeline as one call, used the same way by the CLI, the server and
// the tests: a repaired polygon mesh in, the quad mesh, its Hamiltonian cycles and the
// smooth curves out, with the time each stage took.
#pragma once

#include "meander/closest_points.h"
#include "meander/collapse_needles.h"
#include "meander/curve.h"
#include "meander/flip_caps.h"
#include "meander/hamiltonian.h"
#include "meander/progress.h"
#include "meander/quadrangulate.h"
#include "meander/relax.h"
#include "meander/remesh.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace meander {

// Polygons of star_sides or more vertices split into stars of triangles
// (star_polygons.h; 0: none), then the caps flipped as `caps` says (flip_caps.h), then
// the needles collapsed as `needles` says (collapse_needles.h).
struct SlabMeshOptions {
  int star_sides = 5;
  std::optional<CapFlipOptions> caps = CapFlipOptions{};
  std::optional<NeedleCollapseOptions> needles = NeedleCollapseOptions{};
  friend bool operator==(const SlabMeshOptions&, const SlabMeshOptions&) = default;
};

struct CurveJob {
  // Set: the mesh is first scaled about the origin so that its largest bounding-box side
  // is this long (scaled_to_size), in millimetres, the unit of every length of the job.
  std::optional<double> model_size;
  // Set: the surface is first remeshed evenly (remesh_to_spacing) so that neighbouring
  // passes of the curve lie about this far apart, and the curve's points are then moved
  // onto the input surface; none: the curve follows the input's own faces.
  std::optional<double> spacing;
  // With spacing: rounds of relax_curves (relax.h) that even the gaps between passes.
  int relax = RelaxOptions{}.iterations;
  // With spacing: refuse (InputError) a remeshed surface estimated at more faces; 0: no limit.
  int64_t max_faces = 0;
  Quadrangulation quadrangulation = Quadrangulation::dual_simplest;
  // Set: the mesh is made ready for a variable wire's slabs first, which fold in flat
  // triangles (what `wire --method variable` does); none: it is used as it is.
  std::optional<SlabMeshOptions> slab_mesh;
  CycleOptions cycle;
  CurveOptions curve;
  // false: leave CurveResult::curves empty, for a caller that writes them to `output`
  // or with write_cycle_curves instead of holding them.
  bool sample = true;
  // Not empty: make_curve also writes the curves there (as write_polylines would), and
  // with `sample` false writes a PLY's edges while the cycle is made and its points while
  // the cycle is walked (CycleCurveWriter).
  std::filesystem::path output;
  friend bool operator==(const CurveJob&, const CurveJob&) = default;
};

// Wall-clock seconds per stage, in the order the stages ran.
using StageTimes = std::vector<std::pair<std::string, double>>;

struct CurveResult {
  QuadMesh quads; // of the remeshed surface with CurveJob::spacing
  TriangleCycle cycle;
  Polylines curves; // one closed curve per connected component
  // With CurveJob::spacing: the input surface, which the curves lie on (moved there), and
  // its normal at each point of the curves (what a wire sweeps them with).
  PolygonMesh surface;
  std::vector<Vec3> normals;
  int64_t points_written = 0; // to CurveJob::output
  // By CurveJob::slab_mesh: polygons split, edges flipped, caps cut off the boundary,
  // needles' edges collapsed.
  int64_t stars = 0, cap_flips = 0, cap_cuts = 0, needle_collapses = 0;
};

// The mesh scaled about the origin by size / its largest bounding-box side. Throws
// InputError for a mesh of no extent.
PolygonMesh scaled_to_size(PolygonMesh mesh, double size);

// The edge length of the even mesh on which the curve's passes lie `spacing` apart (their
// median distance), as measured for each quadrangulation (docs/density.md).
double spacing_edge_length(double spacing, Quadrangulation quadrangulation);

// About how many faces the surface remeshed to `spacing` has (remeshed_faces_estimate),
// the mesh first scaled to `model_size` if set: what a caller weighs against its memory
// before any work. 0 without a spacing.
int64_t remeshed_faces(const PolygonMesh& mesh, std::optional<double> model_size, std::optional<double> spacing,
                       Quadrangulation quadrangulation);

// The even remesh (remesh.h) of a mesh that repair() accepted, on which a curve made
// with this quadrangulation has passes `spacing` apart; `input`, if given, is
// ClosestPoints(mesh), built otherwise. Throws ParameterError for quad none (a remeshed
// surface has no quads) or a spacing not smaller than the model, and what remesh
// throws (max_faces: see RemeshOptions).
PolygonMesh remesh_to_spacing(const PolygonMesh& mesh, double spacing, Quadrangulation quadrangulation,
                              int64_t max_faces = 0, const ClosestPoints* input = nullptr);

// What an even surface is made for: the input scaled to model_size (if set) and
// remeshed as remesh_to_spacing does with the other three.
struct EvenSurfaceOptions {
  std::optional<double> model_size;
  double spacing = 0;
  Quadrangulation quadrangulation = Quadrangulation::dual_simplest;
  int64_t max_faces = 0;
  friend bool operator==(const EvenSurfaceOptions&, const EvenSurfaceOptions&) = default;
};

// Those of a job with CurveJob::spacing set.
EvenSurfaceOptions even_surface_options(const CurveJob& job);

// The surface a curve of a spacing is made on: what make_curve makes first, for a caller
// that makes several curves, wires or duotones of one spacing (the studio, whose other
// sliders leave it as it is).
struct EvenSurface {
  EvenSurfaceOptions options;
  PolygonMesh input; // scaled to options.model_size
  ClosestPoints on_input;
  PolygonMesh even; // remesh_to_spacing(input, ...)
};

// Throws what scaled_to_size and remesh_to_spacing throw.
EvenSurface make_even_surface(PolygonMesh mesh, const EvenSurfaceOptions& options);

// Runs the remeshing (with CurveJob::spacing), connectivity, quadrangulation, the cycle,
// control points and smoothing on a mesh that repair() accepted. Takes the mesh by value so its memory is released as soon as
// the quad mesh exists. Appends to `times` if given, and tells `progress` (which may
// cancel it) if given. Throws TopologyError for a quad mesh with boundary under --quad
// catmull-clark or none, Cancelled, and what the stages throw.
CurveResult make_curve(PolygonMesh mesh, const CurveJob& job, StageTimes* times = nullptr, Progress* progress = nullptr);

// The same with the mesh's connectivity already known (RepairResult::connectivity); an
// empty or mismatched one is rebuilt.
CurveResult make_curve(PolygonMesh mesh, Connectivity connectivity, const CurveJob& job, StageTimes* times = nullptr,
                       Progress* progress = nullptr);

// The same on an even surface made for this job (throws UsageError unless
// even.options == even_surface_options(job)): the same result as make_curve on the
// input, without the remesh's time.
CurveResult make_curve(const EvenSurface& even, const CurveJob& job, StageTimes* times = nullptr,
                       Progress* progress = nullptr);

} // namespace meander
