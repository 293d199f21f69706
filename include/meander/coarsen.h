// Coarsening a fine triangle mesh by edge collapses that keep its topology: what remesh()
// starts from when the input is much finer than the target, so that CGAL's remeshing
// works on few faces. meshoptimizer's simplifier, which remesh() used first, changed the
// topology of generated UV spheres and pretzels at any reduction (it does not check the
// link condition) and took 1.2 to 1.9 s on a 1M-triangle sphere (docs/density.md).
#pragma once

#include "meander/mesh.h"

namespace meander {

// The triangle mesh with its edges shorter than `length` collapsed, shortest scale first
// (in passes of rising threshold, each in face order), each into one of its ends, so that
// every vertex of the result is one of the input's, at its position. A collapse is made
// only if the link condition holds (the ends share no neighbour but the edge's opposite
// vertices, and those two are not joined), no edge inside the surface joins two boundary
// vertices, no boundary vertex moves, no boundary loop falls below three edges, no face's
// normal turns by more than 60 degrees and no edge grows longer than 1.5 times `length`:
// so each component keeps its Euler characteristic, boundary loops and orientability.
// Vertices and faces keep their relative order. Deterministic. Requires a manifold
// triangle mesh (repair()'s output); throws InputError for a face that is not a triangle.
// About O(n) for n faces of bounded valence.
PolygonMesh coarsen(const PolygonMesh& mesh, double length);

} // namespace meander
