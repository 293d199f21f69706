// The shell of a surface too thin or too sharply folded for a wall that follows it quad by
// quad (shell.cpp): sampled by CGAL's 3D mesher instead (internal to duotone_shell).
#pragma once

#include "meander/shell.h"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace meander {

// A closed or open triangle surface, each component oriented (a closed one outward), with
// a colour region (0 or 1) per triangle.
struct PaintedSurface {
  std::span<const Vec3> positions;
  std::span<const std::array<int32_t, 3>> triangles;
  std::span<const uint8_t> region;
};

// The shell as two solids, one per region, meeting along the cut: the points inside the
// surface (for an open one, on the side its normals turn from) within the wall's
// thickness of it, each belonging to the region its nearest surface point lies in. Where
// the model is thinner than two walls it is solid. Meshed as a labelled domain by CGAL's
// Mesh_3 (facets about a wall across, within a tenth of one of the surface, the regions'
// common boundary and the surface's own kept as edges), seeded on both sides of the wall,
// so that no part of a thin wall is missed; where a region's neck is narrower than the
// cells, the cells are relabelled or their corners parted (by a twentieth of a cell) so
// that each solid, and the shell they make, is a closed surface. With a clearance > 0,
// the points near where the two solids would meet are left out of both (0.6 of it from the
// cut on the surface, 0.3 of it from the middle of a thin part), the cells there as small
// as the clearance, and the solids (no longer meeting) measured apart (SplitShell::apart).
// Deterministic. Throws TopologyError when a solid is not one closed, outward surface
// clear of itself, or the pieces come nearer than 0.45 of the clearance.
SplitShell sampled_shell(const PaintedSurface& surface, double thickness, double clearance);

// The least distance from a corner or side midpoint of either solid's faces to the other
// (out.apart, out.apart_at), and per solid the faces with such a point nearer than `near`.
std::array<std::vector<int32_t>, 2> measure_apart(SplitShell& out, double near);

// A point as the shells' messages name it: "(x, y, z)".
std::string place(Vec3 p);

} // namespace meander
