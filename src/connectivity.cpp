#include "meander/connectivity.h"

namespace meander {

Connectivity build_connectivity(const PolygonMesh& mesh) {
  const int32_t nv = mesh.num_vertices();
  const int32_t nf = mesh.num_faces();
  const int32_t nh = mesh.num_corners();
  Connectivity c;
  c.halfedge_face.resize(size_t(nh));
  for (int32_t f = 0; f < nf; ++f)
    for (int32_t h = mesh.face_start[f]; h < mesh.face_start[f + 1]; ++h) c.halfedge_face[size_t(h)] = f;

  // Counting sort of halfedges by their lower vertex (linear, unlike a hash map or a
  // comparison sort); the upper vertex is kept per halfedge for the grouping pass.
  std::vector<int32_t> bucket_start(size_t(nv) + 1, 0);
  std::vector<int32_t> upper(static_cast<size_t>(nh));
  for (int32_t f = 0; f < nf; ++f) {
    const int32_t b = mesh.face_start[f], e = mesh.face_start[f + 1];
    for (int32_t h = b; h < e; ++h) {
      const int32_t u = mesh.face_vertices[size_t(h)];
      const int32_t v = mesh.face_vertices[size_t(h + 1 == e ? b : h + 1)];
      const int32_t lo = u < v ? u : v;
      upper[size_t(h)] = u < v ? v : u;
      ++bucket_start[size_t(lo) + 1];
    }
  }
  for (int32_t v = 0; v < nv; ++v) bucket_start[size_t(v) + 1] += bucket_start[size_t(v)];
  std::vector<int32_t> sorted(static_cast<size_t>(nh));
  {
    std::vector<int32_t> fill(bucket_start.begin(), bucket_start.end() - 1);
    for (int32_t f = 0; f < nf; ++f) {
      const int32_t b = mesh.face_start[f], e = mesh.face_start[f + 1];
      for (int32_t h = b; h < e; ++h) {
        const int32_t u = mesh.face_vertices[size_t(h)];
        const int32_t v = mesh.face_vertices[size_t(h + 1 == e ? b : h + 1)];
        sorted[size_t(fill[size_t(u < v ? u : v)]++)] = h;
      }
    }
  }

  // Group each bucket by upper vertex. slot[v] holds the edge id last created for upper
  // vertex v and stamp[v] the lower vertex it was created for, so no clearing is needed.
  std::vector<int32_t> stamp(size_t(nv), -1), slot(size_t(nv), -1);
  std::vector<int32_t> degree;
  c.halfedge_edge.assign(size_t(nh), -1);
  c.edge_vertices.reserve(size_t(nh) / 2 + 1);
  degree.reserve(size_t(nh) / 2 + 1);
  for (int32_t lo = 0; lo < nv; ++lo) {
    for (int32_t i = bucket_start[size_t(lo)]; i < bucket_start[size_t(lo) + 1]; ++i) {
      const int32_t h = sorted[size_t(i)];
      const int32_t hi = upper[size_t(h)];
      if (stamp[size_t(hi)] != lo) {
        stamp[size_t(hi)] = lo;
        slot[size_t(hi)] = int32_t(c.edge_vertices.size());
        c.edge_vertices.push_back({lo, hi});
        degree.push_back(0);
      }
      c.halfedge_edge[size_t(h)] = slot[size_t(hi)];
      ++degree[size_t(slot[size_t(hi)])];
    }
  }

  const int32_t ne = int32_t(c.edge_vertices.size());
  c.edge_start.assign(size_t(ne) + 1, 0);
  for (int32_t e = 0; e < ne; ++e) c.edge_start[size_t(e) + 1] = c.edge_start[size_t(e)] + degree[size_t(e)];
  c.edge_halfedges.resize(size_t(nh));
  std::vector<int32_t> fill(c.edge_start.begin(), c.edge_start.end() - 1);
  for (int32_t h = 0; h < nh; ++h) c.edge_halfedges[size_t(fill[size_t(c.halfedge_edge[size_t(h)])]++)] = h;
  return c;
}

} // namespace meander
