// A surface painted in two regions, printed in two colours (issue 38; the paper's Section
// 6: "cutting the surface into two 2-manifolds with boundaries ... turned to solid
// shapes"): the surface thickened into a shell and cut along the regions' common boundary,
// straight through the wall, into two solids, one per region.
#pragma once

#include "meander/duotone.h"

#include <array>
#include <cstdint>

namespace meander {

struct ShellOptions {
  double thickness = 0; // the wall, > 0, in mesh units
  // The thinnest wall the printer makes: where the wall must be thinner (the model is
  // thinner than two walls there), the result says so. 0: no floor.
  double min_thickness = 0;
  // > 0: the two pieces drawn apart by this much, to be printed apart and put together
  // (each region's boundary moved half of it back from the cut on both surfaces).
  double clearance = 0;
};

struct SplitShell {
  // solids[k] is colour region k thickened: the region itself (its outside), the region
  // moved inward (its inside), and a wall along each of its boundary edges joining the
  // two. Each is closed and outward; they meet along the walls at the regions' common
  // boundary (the same triangles, opposite ways round) and overlap nowhere, so together
  // they are the shell.
  std::array<PolygonMesh, 2> solids;
  std::array<double, 2> volumes{}; // of the solids (the divergence theorem), positive
  // Where the wall is thinner than asked (the model is thinner than two walls there, or
  // it bends too sharply for the inside to follow), counted in the quads' corners.
  int32_t reduced_corners = 0;
  int32_t below_floor_corners = 0; // thinner than ShellOptions::min_thickness
  double thinnest = 0;             // the thinnest wall, at a corner
  Vec3 thinnest_at;                // that corner
  // With a clearance: the least distance from a corner or side midpoint of either
  // solid's faces to the other, and that point.
  double apart = 0;
  Vec3 apart_at;
  // The wall could not follow the quads (the model is thinner than two walls, or folds too
  // sharply, or the surface touches itself, or the gap is too wide for some quads): the
  // shell was sampled instead, solid where the model is thinner than two walls, its
  // outside within a tenth of the wall of the surface.
  bool sampled = false;
};

// The duotone's surface thickened into a shell and cut along its separating curves
// (duotone_regions with `style`: the tiles' curves), straight through the wall. A closed
// component is thickened inward, an open one to the side its quads' normals turn away
// from (its surface boundary walled like the cut). Each corner of the quads moves in
// along its normal until it lies the thickness from the surface (or, in a part thinner
// than two walls, 0.45 of the way across), then onto the points that lie that far from
// the surface (near a sharp bend, away from its other side); corners of quads whose
// inside would fold over or cross itself or the outside are drawn back. The tiles inside
// each quad half move with its corners, so that no sliver of a tile turns over.
// With a clearance each region is drawn back from the cut (duotone_regions' gaps: half
// the clearance on each quad side, on the outside and on the inside, whichever side is
// shorter), so the solids no longer meet: each has its own walls.
// Where that inside still crosses itself or the outside (a part thinner than two walls
// that folds sharply: a scan's ears), the surface crosses or touches itself, or the gap
// would leave too little of some quads (over a fifth of one, or pieces drawn back at a
// slant that still come too near), the shell is sampled instead (SplitShell::sampled:
// CGAL's Mesh_3, solid where the model is thinner than two walls; seconds to a minute for
// a 100 mm model with a 1.5 mm wall, minutes with a clearance, whose gap is meshed in
// cells as small as it; its pieces are drawn back 0.6 of the clearance from the cut on the
// surface and kept 0.6 of it apart across a thin part). Deterministic. Throws
// ParameterError for a thickness that is not a positive number or is below min_thickness,
// a negative clearance or one wider than a sixth of the quads' median side (the gap would
// leave crumbs of the colours' bands); TopologyError, naming a place, for a non-orientable
// surface (it has no inside: a Möbius band), a sampled solid that touches or crosses
// itself, or, with a clearance, pieces that cannot be drawn apart. O(n log n) for n
// triangles of the regions, plus the self-intersection searches (printability.h) of the
// surface, each solid and the whole shell.
SplitShell duotone_shell(const Duotone& duotone, TileStyle style, const ShellOptions& options);

} // namespace meander
