// Edge flips that remove caps (triangles with one angle near 180 degrees) from the
// input before a variable wire is built on it.
//
// A cap's dual-of-Simplest triangles are needles on one line whatever its face point:
// the cycle turns back on itself there and the slabs standing on it overlap at any
// thickness (docs/wires.md, "Where slabs fold"). Flipping the cap's long edge replaces
// the cap and its neighbour by two triangles whose largest angle is smaller; the surface
// moves by no more than the cap's height, and less where the pair is flat. On the
// boundary, where there is no edge to flip, the cap is cut off.
#pragma once

#include "meander/mesh.h"

#include <cstdint>

namespace meander {

struct CapFlipOptions {
  // A triangle whose largest angle exceeds this is a cap.
  double cap_angle_degrees = 120;
  // A flip is made only if it moves the surface by at most this fraction of the flipped
  // edge's length (the distance between the old and the new edge's lines): across a
  // crease it would cut the corner off. A flat cap moves it little wherever it lies.
  double max_move = 0.1;
  int max_passes = 4; // each pass is linear; a flip can make a neighbour's flip possible
  friend bool operator==(const CapFlipOptions&, const CapFlipOptions&) = default;
};

struct CapFlips {
  PolygonMesh mesh;
  int64_t flips = 0;
  int64_t cuts = 0; // caps on the boundary, removed
};

// Flips the edge opposite a cap's largest angle when the neighbour across it is a
// triangle wound the same way, the flip lowers the pair's largest angle, moves the
// surface by at most options.max_move, folds neither new triangle over (each faces the
// way the pair did) and does not make an edge the mesh already has (it stays manifold).
// A cap whose long edge lies on the boundary is cut off instead (the boundary then runs
// through its apex) when its height is within options.max_move of that edge and its
// apex is not on the boundary already. Faces other than triangles, non-manifold and
// misoriented edges are left as they are; the vertices do not change. Deterministic;
// O(corners) per pass.
CapFlips flip_caps(PolygonMesh mesh, const CapFlipOptions& options = {});

} // namespace meander
