// Vertex and face orders that keep what lies together on the surface together in memory.
//
// Every stage after reading follows the mesh's adjacency, so its speed depends on how
// far apart in memory neighbouring elements lie. Meshes from most tools keep neighbours
// near each other, but not all, and a scattered one makes every stage several times
// slower (docs/curve.md, "Large meshes"). A mesh found scattered is put in an
// order where vertices and faces follow a space-filling curve.
#pragma once

#include "meander/mesh.h"

#include <cstdint>
#include <vector>

namespace meander {

// A new order of a mesh's elements: new face f is input face face_order[f], and input
// vertex v becomes new vertex vertex_rank[v].
struct MeshOrder {
  std::vector<int32_t> face_order;
  std::vector<int32_t> vertex_rank;
};

// Whether the mesh is large enough for its order to matter (2^18 faces or more) and
// scattered: runs of 1024 consecutive faces, 64 of them spread over the mesh, touch on
// average more than 64 blocks of 1024 vertex indices. A mesh whose faces follow its
// surface touches a few; one whose vertices come in a few streams, each in order (as a
// subdivision numbers them by level), a few dozen. Reads only the indices, whatever they
// hold.
bool is_scattered(const PolygonMesh& mesh);

// Vertices by the Morton code of their positions (2^10 cells a side of the bounding box
// of the finite positions), faces by that of their first vertex, ties in input order.
// Every face index must be in range. O(corners).
MeshOrder locality_order(const PolygonMesh& mesh);

// The mesh in that order; each face keeps its first corner and its orientation.
PolygonMesh reordered(const PolygonMesh& mesh, const MeshOrder& order);

// The mesh that `reordered` was given, from what it returned and the same order.
PolygonMesh restored(const PolygonMesh& mesh, const MeshOrder& order);

} // namespace meander
