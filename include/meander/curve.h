// From the triangle cycle to a smooth closed curve (paper Section 3, "Control Vertex
// Position Computation", and the B-spline / Catmull-Rom curves it mentions).
#pragma once

#include "meander/hamiltonian.h"
#include "meander/mesh.h"

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace meander {

// One control point per triangle of each cycle, at the paper's weighted centre
// (2 p_apex + p + n) / 4: the triangle read as a quad whose apex is doubled. O(triangles).
Polylines control_polygons(const QuadMesh& quads, const TriangleCycle& cycle);

enum class Smoothing {
  bspline,     // uniform cubic B-spline approximating the control polygon (C2)
  catmull_rom, // centripetal Catmull-Rom interpolating it (no cusps or self-loops per segment)
  none,        // the control polygon itself
};

// Parses "bspline" | "catmull-rom" | "none"; throws UsageError otherwise.
Smoothing parse_smoothing(std::string_view name);

// The uniform cubic B-spline basis at u in [0, 1): the weights of control points i-1,
// i, i+1, i+2 for the point of segment i that smooth_curves samples at u (wires blend
// surface normals with the same weights).
std::array<float, 4> bspline_weights(float u);

struct CurveOptions {
  Smoothing smoothing = Smoothing::bspline;
  int samples = 4; // points per control polygon segment, >= 1
  friend bool operator==(const CurveOptions&, const CurveOptions&) = default;
};

// Samples each closed control polygon into a closed smooth polyline with
// options.samples points per segment (none: the control polygon as is). O(output).
// Throws UsageError if samples < 1 or samples * points exceeds 2^31.
Polylines smooth_curves(const Polylines& control, const CurveOptions& options = {});

// smooth_curves(control_polygons(quads, cycle), options) without the control polygons in
// memory: what the pipeline uses on large meshes.
Polylines cycle_curves(const QuadMesh& quads, const TriangleCycle& cycle, const CurveOptions& options = {});

// Points per control polygon segment for curves of `control_points` control points in
// all: options.samples, or 1 for Smoothing::none. Throws UsageError if samples < 1 or
// the curves would hold 2^31 points or more.
int points_per_segment(int64_t control_points, const CurveOptions& options);

// Points [begin, end) of the closed curves through the control points of the cycle
// triangles `order`, curve j made of order[start[j]] .. order[start[j + 1] - 1], points
// counted over all curves, points_per_segment of them a segment, into dst[0, end - begin).
// A point depends only on its segment's four control points, so any block gives the same
// floats as cycle_curves, even while `order` is only the part of a walk made so far (a
// streaming writer samples whatever block it writes). options must be valid.
void sample_cycle_curves(const QuadMesh& quads, std::span<const int32_t> order, std::span<const int32_t> start,
                         const CurveOptions& options, int64_t begin, int64_t end, Vec3* dst);

} // namespace meander
