// Edge collapses that remove needles (triangles with one angle near 0 degrees) from the
// input before a variable wire is built on it.
//
// Around a needle every dual-of-Simplest triangle the cycle can take has a small angle
// at an end of its diagonal, which lays a rung along the direction of travel; where
// needles lie side by side (a scan's strip of long thin faces) no spanning tree avoids
// them, and the slabs there overlap at any size (docs/wires.md, "Where slabs fold").
// Merging the ends of a needle's short edge removes it and its neighbour across that
// edge; the surface moves by at most half that edge's length.
#pragma once

#include "meander/mesh.h"

#include <cstdint>

namespace meander {

struct NeedleCollapseOptions {
  // A triangle whose smallest angle is below this is a needle.
  double needle_angle_degrees = 5;
  // A short edge is collapsed only if it is at most this fraction of its needle's
  // longest side: the end of a cap's long edge is a small angle too, but its short
  // edge is half the cap long, and merging it would move the surface that far.
  double max_move = 0.1;
  int max_passes = 4; // each pass is linear; the faces around a collapse wait for the next
  friend bool operator==(const NeedleCollapseOptions&, const NeedleCollapseOptions&) = default;
};

struct NeedleCollapses {
  PolygonMesh mesh;
  int64_t collapses = 0;
};

// Collapses the edge facing a needle's smallest angle into its midpoint (into its end
// on the boundary when only one end is there; an edge whose ends are both on the
// boundary only if it is a boundary edge itself) when every face around its ends is a
// triangle, the collapse keeps the mesh manifold (the ends share no neighbour but the
// needle's and its neighbour's third corners), turns no face around them by more than
// 60 degrees and makes no two faces alike. Vertices left unused are dropped, the others
// keep their order; faces keep theirs. Faces other than triangles are left as they are.
// Deterministic; O(corners) per pass for bounded valence.
NeedleCollapses collapse_needles(PolygonMesh mesh, const NeedleCollapseOptions& options = {});

} // namespace meander
