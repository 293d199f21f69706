#include "meander/pipeline.h"

#include "meander/connectivity.h"
#include "meander/curve_writer.h"
#include "meander/error.h"
#include "meander/io.h"
#include "meander/star_polygons.h"

#include <chrono>
#include <optional>
#include <string>

namespace meander {

namespace {

class Stopwatch {
public:
  explicit Stopwatch(StageTimes* times) : times_(times), start_(std::chrono::steady_clock::now()) {}
  void lap(const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    if (times_) times_->emplace_back(stage, std::chrono::duration<double>(now - start_).count());
    start_ = now;
  }

private:
  StageTimes* times_;
  std::chrono::steady_clock::time_point start_;
};

} // namespace

CurveResult make_curve(PolygonMesh mesh, const CurveJob& job, StageTimes* times) {
  return make_curve(std::move(mesh), Connectivity(), job, times);
}

CurveResult make_curve(PolygonMesh mesh, Connectivity connectivity, const CurveJob& job, StageTimes* times) {
  Stopwatch watch(times);
  CurveResult result;
  if (job.slab_mesh) {
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
    watch.lap("slab mesh");
  }
  if (connectivity.halfedge_edge.size() != mesh.face_vertices.size() || connectivity.edge_start.empty()) {
    connectivity = build_connectivity(mesh);
    watch.lap("connectivity");
  }
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
  watch.lap("quadrangulate");
  std::optional<CycleCurveWriter> writer;
  if (!job.sample && !job.output.empty()) writer.emplace(result.quads, job.curve, job.output);
  result.cycle = hamiltonian_cycle(result.quads, job.cycle, writer ? writer->observer() : nullptr);
  watch.lap("cycle");
  if (writer) {
    result.points_written = writer->finish(result.cycle);
    watch.lap("smooth + write");
  }
  if (job.sample) {
    result.curves = cycle_curves(result.quads, result.cycle, job.curve);
    watch.lap("smooth");
    if (!job.output.empty()) {
      write_polylines(result.curves, job.output);
      result.points_written = int64_t(result.curves.points.size());
      watch.lap("write curve");
    }
  }
  return result;
}

} // namespace meander
