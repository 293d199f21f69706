// Edge connectivity of a polygon mesh, keyed by the unordered vertex pair.
//
// Keying edges by {min, max} rather than pairing a halfedge (a,b) with its reverse (b,a)
// keeps boundary edges, works on non-orientable surfaces (a Möbius band crosses an edge
// the same way from both sides) and counts non-manifold edges instead of dropping them.
#pragma once

#include "meander/default_init.h"
#include "meander/mesh.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace meander {

// Halfedge h is corner h of the mesh: it runs from face_vertices[h] to the next vertex
// of its face. Edge e joins edge_vertices[e] = {lo, hi} (lo < hi) and is crossed by the
// halfedges edge_halfedges[edge_start[e] .. edge_start[e+1]) in increasing order:
// 1 on a boundary edge, 2 on a manifold interior edge, more on a non-manifold edge.
// Edges are numbered by increasing (lo, hi). face_of(h) is the face of halfedge h: found
// by division when every face has `face_size` corners (a triangle or a quad mesh), from
// halfedge_face otherwise (face_size 0), since an array as long as the corners is among
// the largest the pipeline holds, and a large array costs more to take fresh than to
// fill (docs/curve.md, "Large meshes").
// The arrays are not zeroed when sized (default_init.h): each is written whole right after.
struct Connectivity {
  UninitVector<int32_t> halfedge_edge;
  UninitVector<int32_t> halfedge_face;
  int32_t face_size = 0;
  UninitVector<std::array<int32_t, 2>> edge_vertices;
  UninitVector<int32_t> edge_start;
  UninitVector<int32_t> edge_halfedges;

  int32_t face_of(int32_t h) const {
    // Division by a constant is a multiplication; by a variable, ten times as slow.
    if (face_size == 3) return int32_t(uint32_t(h) / 3);
    if (face_size == 4) return int32_t(uint32_t(h) / 4);
    return face_size > 0 ? h / face_size : halfedge_face[size_t(h)];
  }
  int32_t num_edges() const { return edge_start.empty() ? 0 : int32_t(edge_start.size()) - 1; }
  int32_t edge_degree(int32_t e) const { return edge_start[e + 1] - edge_start[e]; }
  std::span<const int32_t> halfedges(int32_t e) const {
    return {edge_halfedges.data() + edge_start[e], size_t(edge_degree(e))};
  }
};

// Builds the edge connectivity in O(corners + vertices) time for bounded valence: a
// counting sort by the lower vertex, then a sort of each vertex's few halfedges by the
// upper vertex (O(k log k) for a vertex of valence k). No hashing.
// Requires every face index to be in range (readers guarantee it); faces of any size.
Connectivity build_connectivity(const PolygonMesh& mesh);

// The halfedge after h in its face.
inline int32_t next_halfedge(const PolygonMesh& mesh, const Connectivity& c, int32_t h) {
  const int32_t f = c.face_of(h);
  if (c.face_size > 0) return h + 1 == (f + 1) * c.face_size ? f * c.face_size : h + 1;
  return h + 1 == mesh.face_start[f + 1] ? mesh.face_start[f] : h + 1;
}

// The vertex halfedge h points to.
inline int32_t halfedge_target(const PolygonMesh& mesh, const Connectivity& c, int32_t h) {
  return mesh.face_vertices[next_halfedge(mesh, c, h)];
}

} // namespace meander
