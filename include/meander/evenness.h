// How evenly closed curves cover a surface (issue 34, "Evenness"): the gap between
// neighbouring passes of the curves, and how far the surface lies from them. What the
// tests hold a covering curve to and what `meander info MESH --curve CURVE` prints.
#pragma once

#include "meander/mesh.h"

#include <cstdint>

namespace meander {

struct EvennessOptions {
  // Arc-length step at which every curve is resampled before measuring, in mesh units;
  // 0: spacing_estimate / 8, or coarser where that would make more than 2^24 points.
  double step = 0;
  // Area-weighted random points of the surface whose distance to the curves is the
  // coverage, >= 1.
  int32_t surface_samples = 100000;
  uint64_t seed = 1;
};

// Distances in mesh units.
struct EvennessReport {
  // Surface area / total curve length: the spacing of an even covering curve.
  double spacing_estimate = 0;
  double step = 0;      // of the resampling (each curve's own is step or a little less)
  int32_t points = 0;   // resampled curve points
  int32_t unpaired = 0; // points with no other pass within 32 spacing estimates (left out of the gap figures)
  // Gap at a resampled point p: the distance to the nearest resampled point q that lies
  // farther from p along the curve (the shorter way round) than 1.4 |p - q|, any point of
  // another curve counting. Both sides of a hairpin count; the same stretch does not.
  double gap_median = 0, gap_mean = 0;
  double gap_cv = 0; // standard deviation / mean
  double gap_p5 = 0, gap_p95 = 0;
  // Coverage: the distance from each surface sample to the nearest resampled point.
  int32_t surface_samples = 0;
  double coverage_p99 = 0, coverage_max = 0;
  Vec3 farthest{}; // the sample at coverage_max (the first such): where the surface is least covered
  friend bool operator==(const EvennessReport&, const EvennessReport&) = default;
};

// Measures closed `curves` on `surface` (faces fanned from their first vertex into
// triangles; indices in range, as read_mesh gives). Percentiles interpolate between
// ranks. The result is the same for the same input and seed whatever the number of
// threads (oneTBB).
// Nearest points come from a uniform hash grid of cells of spacing_estimate, searched in
// rings of cells up to 32 of them: for curves that lie on the surface at about that
// spacing, O(P + F + S log F) time and O(P + F + S) memory for P resampled points, F
// faces and S samples; a query whose answer lies k cells away visits O(k^3) cells.
// Throws InputError for no curves, an open or empty curve, one of fewer than 3 points,
// a non-finite point or position, a curve point outside the surface's bounding box grown
// by a tenth of its diagonal, a curve of zero length, a surface of zero area,
// curves where no point has another pass, or a surface sample farther than 32 spacing
// estimates from every curve point (curves of another mesh, or of only some of its
// components); ParameterError for a negative or non-finite step, surface_samples < 1, or
// a step that would make 2^31 points or more.
EvennessReport measure_evenness(const PolygonMesh& surface, const Polylines& curves,
                                const EvennessOptions& options = {});

} // namespace meander
