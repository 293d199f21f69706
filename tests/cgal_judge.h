// CGAL as an independent judge of Meander's printability report, in the tests only:
// the same mesh loaded into a CGAL::Surface_mesh (polygons fanned from their first
// vertex, as Meander does) and asked what Polygon_mesh_processing says about it.
#pragma once

#include "meander/mesh.h"

namespace meander::test {

struct CgalVerdict {
  // Surface_mesh took every triangle: it refuses faces that would make an edge
  // non-manifold or run against their neighbours. The rest is left false/0 otherwise.
  bool loaded = false;
  bool closed = false;             // CGAL::is_closed
  bool self_intersecting = false;  // PMP::does_self_intersect
  double volume = 0;               // PMP::volume, only when closed
  bool outward = false;            // PMP::is_outward_oriented, only when closed
};

CgalVerdict cgal_judge(const PolygonMesh& mesh);

// The least distance from a vertex or edge midpoint of `from` to the surface of `to`
// (CGAL's AABB tree).
double cgal_least_distance(const PolygonMesh& from, const PolygonMesh& to);

} // namespace meander::test
