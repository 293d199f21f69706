// Edge connectivity of a polygon mesh, keyed by the unordered vertex pair.
//
// Keying edges by {min, max} rather than pairing a halfedge (a,b) with its reverse (b,a)
// keeps boundary edges, works on non-orientable surfaces (a Möbius band crosses an edge
// the same way from both sides) and counts non-manifold edges instead of dropping them.
#pragma once

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
// Edges are numbered by increasing (lo, hi).
struct Connectivity {
  std::vector<int32_t> halfedge_edge;
  std::vector<int32_t> halfedge_face;
  std::vector<std::array<int32_t, 2>> edge_vertices;
  std::vector<int32_t> edge_start;
  std::vector<int32_t> edge_halfedges;

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
  int32_t f = c.halfedge_face[h];
  return h + 1 == mesh.face_start[f + 1] ? mesh.face_start[f] : h + 1;
}

// The vertex halfedge h points to.
inline int32_t halfedge_target(const PolygonMesh& mesh, const Connectivity& c, int32_t h) {
  return mesh.face_vertices[next_halfedge(mesh, c, h)];
}

} // namespace meander
