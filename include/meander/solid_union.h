// Closed solids by CGAL's exact predicates: the union of two, for bridges fused into a
// wire (bridges.h), and which points one holds, for where they may end.
#pragma once

#include "meander/mesh.h"

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace meander {

// Where a vertex of the union comes from.
enum class UnionVertex : uint8_t {
  first,   // a vertex of the first mesh
  second,  // of the second
  crossing // made where their surfaces cross
};

struct SolidUnion {
  PolygonMesh mesh;
  std::vector<UnionVertex> origin; // per vertex
};

// The boundary of the union of the solids that two closed, outward meshes bound (neither
// intersecting itself; they may intersect each other), as triangles, by CGAL's
// corefinement (Polygon Mesh Processing, exact predicates). Throws InputError when a
// mesh is not closed, has a polygon of more than four corners or intersects itself,
// naming it ("the wire intersects itself"), and TopologyError when CGAL cannot make the
// union a manifold surface. The points made in double are
// rounded to floats; faces that rounding flattens or turns into their neighbours are
// collapsed. Deterministic.
SolidUnion unite_solids(const PolygonMesh& first, const PolygonMesh& second, std::string_view first_name = "first mesh",
                        std::string_view second_name = "second mesh");

// Per point, 1 if it lies inside the solid a closed, outward mesh bounds, 0 outside or
// on it, by CGAL's Side_of_triangle_mesh (a ray's crossings, exact predicates): unlike
// the side of the nearest face, the same answer wherever that face is shared. Throws
// InputError as unite_solids does for a mesh that is not closed. O(n log n + p log n).
std::vector<uint8_t> inside_solid(const PolygonMesh& mesh, std::span<const Vec3> points, std::string_view name = "mesh");

} // namespace meander
