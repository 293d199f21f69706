// An even (isotropic) triangle mesh of a surface at a chosen edge length, with the
// surface's topology: what a curve of a chosen spacing is made on, so that its density
// is the maker's and not the input's (paper Section 6, "curves independent of the
// mesh"). CGAL's isotropic remeshing (Botsch and Kobbelt: splits, collapses, flips,
// tangential relaxation), every vertex projected onto the input surface.
#pragma once

#include "meander/closest_points.h"
#include "meander/mesh.h"

#include <cstdint>

namespace meander {

struct RemeshOptions {
  double edge_length = 0; // the target, > 0, in the mesh's units
  int iterations = 3;     // of splits, collapses, flips and relaxation
  // Refuse (InputError) before any work a result estimated at more faces; 0: no limit.
  int64_t max_faces = 0;
};

// The area of the faces, each polygon fanned from its first vertex (as the writers
// triangulate it). O(n).
double surface_area(const PolygonMesh& mesh);

// About as many faces as remesh() makes of this surface at this edge length, rather more
// than fewer: 1.4 times its area over that of an equilateral triangle of that side
// (remesh makes 1.1 to 1.36 times as many). O(n).
int64_t remeshed_faces_estimate(const PolygonMesh& mesh, double edge_length);

// The surface of a mesh that repair() accepted, as an even triangle mesh whose vertices
// lie on it (surface: ClosestPoints(mesh), which the caller may hold already). Each
// component keeps its Euler characteristic, boundary loops and orientability: a
// non-orientable one (a Möbius band) is cut along a seam of edges into an orientable
// one, remeshed with its boundary edges (the seam's two sides among them) kept, split to
// the target length first, and glued back along the seam. A triangle mesh of more than 8
// times the faces estimated is first coarsened (coarsen.h) to about 5 times as many,
// polygons of more than four corners are cut into triangles (ears, then Delaunay flips,
// in the polygon's plane) and faces whose corners lie on a line are taken away.
// Deterministic: the same bytes whatever the heap holds. Throws ParameterError for an edge length that is
// not a positive number, InputError when the estimate exceeds options.max_faces (naming
// it), TopologyError when the remeshed surface's topology differs (a part thinner than
// the edge length, or a component smaller than it). About O(n + m log m) for n input
// and m output faces.
PolygonMesh remesh(const PolygonMesh& mesh, const RemeshOptions& options, const ClosestPoints& surface);
PolygonMesh remesh(const PolygonMesh& mesh, const RemeshOptions& options);

} // namespace meander
