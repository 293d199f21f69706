// Splitting large polygons into stars of triangles before a variable wire is built on
// them.
//
// A polygon's dual-of-Simplest triangles all meet at its one face point. In a polygon of
// many sides that is warped or uneven (a hexahedral model's twisted hexagons) some of
// them are flat, and the slabs standing on them fold over each other; genus3hexa1's
// variable wire crossed itself at six seeds of eight. Split into triangles around its
// centroid, each piece gets a face point of its own, at its incentre.
#pragma once

#include "meander/mesh.h"

#include <cstdint>

namespace meander {

struct StarredPolygons {
  PolygonMesh mesh;
  int64_t stars = 0; // polygons split
};

// Every face of min_sides or more vertices becomes a fan of triangles (centre, v_k,
// v_k+1) in the face's own orientation around a new vertex at the centroid of its
// corners; other faces are kept as they are, in order. New vertices follow the old ones.
// O(corners).
StarredPolygons star_polygons(PolygonMesh mesh, int min_sides = 5);

} // namespace meander
