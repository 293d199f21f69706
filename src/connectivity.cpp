#include "meander/connectivity.h"

#include <algorithm>

namespace meander {

Connectivity build_connectivity(const PolygonMesh& mesh) {
  const int32_t nv = mesh.num_vertices();
  const int32_t nf = mesh.num_faces();
  const int32_t nh = mesh.num_corners();
  Connectivity c;
  c.halfedge_face.resize(size_t(nh));
  // Until the end, halfedge_edge holds each halfedge's upper vertex: reusing the output
  // array spares a temporary as large as the mesh (fresh pages cost more than the work).
  std::vector<int32_t>& upper = c.halfedge_edge;
  upper.resize(size_t(nh));
  std::vector<int32_t> bucket(size_t(nv) + 1, 0);
  for (int32_t f = 0; f < nf; ++f) {
    const int32_t b = mesh.face_start[f], e = mesh.face_start[f + 1];
    for (int32_t h = b; h < e; ++h) {
      const int32_t u = mesh.face_vertices[size_t(h)];
      const int32_t v = mesh.face_vertices[size_t(h + 1 == e ? b : h + 1)];
      c.halfedge_face[size_t(h)] = f;
      upper[size_t(h)] = std::max(u, v);
      ++bucket[size_t(std::min(u, v)) + 1];
    }
  }
  for (int32_t v = 0; v < nv; ++v) bucket[size_t(v) + 1] += bucket[size_t(v)];

  // Counting sort by lower vertex (linear, unlike a hash map or a comparison sort).
  // Placing advances bucket[lo] to the end of lo's range, which is where lo+1's begins.
  std::vector<int32_t>& sorted = c.edge_halfedges;
  sorted.resize(size_t(nh));
  for (int32_t f = 0; f < nf; ++f) {
    const int32_t b = mesh.face_start[f], e = mesh.face_start[f + 1];
    for (int32_t h = b; h < e; ++h) {
      const int32_t u = mesh.face_vertices[size_t(h)];
      const int32_t v = mesh.face_vertices[size_t(h + 1 == e ? b : h + 1)];
      sorted[size_t(bucket[size_t(std::min(u, v))]++)] = h;
    }
  }

  // Within a lower vertex's range (about half its valence), order by upper vertex so the
  // halfedges of each edge become contiguous; equal keys keep increasing halfedge order.
  auto by_upper = [&](int32_t a, int32_t b) { return upper[size_t(a)] < upper[size_t(b)]; };
  c.edge_vertices.reserve(size_t(nh) / 2 + 1);
  c.edge_start.reserve(size_t(nh) / 2 + 2);
  for (int32_t lo = 0, first = 0; lo < nv; first = bucket[size_t(lo)], ++lo) {
    const int32_t last = bucket[size_t(lo)];
    int32_t* range = sorted.data() + first;
    const int32_t n = last - first;
    if (n > 32) {
      std::stable_sort(range, range + n, by_upper);
    } else {
      for (int32_t i = 1; i < n; ++i)
        for (int32_t j = i; j > 0 && by_upper(range[j], range[j - 1]); --j) std::swap(range[j], range[j - 1]);
    }
    for (int32_t i = 0; i < n; ++i)
      if (i == 0 || upper[size_t(range[i])] != upper[size_t(range[i - 1])]) {
        c.edge_vertices.push_back({lo, upper[size_t(range[i])]});
        c.edge_start.push_back(first + i);
      }
  }
  c.edge_start.push_back(nh);
  for (int32_t e = 0; e < c.num_edges(); ++e)
    for (int32_t i = c.edge_start[size_t(e)]; i < c.edge_start[size_t(e) + 1]; ++i) c.halfedge_edge[size_t(sorted[size_t(i)])] = e;
  return c;
}

} // namespace meander
