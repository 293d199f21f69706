// The union of two closed solids, for bridges fused into a wire (bridges.h).
#pragma once

#include "meander/mesh.h"

#include <cstdint>
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

} // namespace meander
