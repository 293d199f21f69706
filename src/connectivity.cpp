#include "meander/connectivity.h"

#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meander {

namespace {

// Fixed blocks of vertices, so that the edge numbering does not depend on how the
// threads share the work.
constexpr int32_t kVertexBlock = 1 << 15;

void for_each_face(const PolygonMesh& mesh, auto&& body) {
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, mesh.num_faces(), 1 << 14), [&](const tbb::blocked_range<int32_t>& r) {
    for (int32_t f = r.begin(); f < r.end(); ++f) {
      const int32_t b = mesh.face_start[f], e = mesh.face_start[f + 1];
      for (int32_t h = b; h < e; ++h)
        body(f, h, mesh.face_vertices[size_t(h)], mesh.face_vertices[size_t(h + 1 == e ? b : h + 1)]);
    }
  });
}

} // namespace

Connectivity build_connectivity(const PolygonMesh& mesh) {
  const int32_t nv = mesh.num_vertices();
  const int32_t nh = mesh.num_corners();
  Connectivity c;
  c.halfedge_face.resize(size_t(nh));
  // Until the end, halfedge_edge holds each halfedge's upper vertex: reusing the output
  // array spares a temporary as large as the mesh (fresh pages cost more than the work).
  std::vector<int32_t>& upper = c.halfedge_edge;
  upper.resize(size_t(nh));
  std::vector<int32_t> bucket(size_t(nv) + 1, 0);
  for_each_face(mesh, [&](int32_t f, int32_t h, int32_t u, int32_t v) {
    c.halfedge_face[size_t(h)] = f;
    upper[size_t(h)] = std::max(u, v);
    std::atomic_ref<int32_t>(bucket[size_t(std::min(u, v)) + 1]).fetch_add(1, std::memory_order_relaxed);
  });
  for (int32_t v = 0; v < nv; ++v) bucket[size_t(v) + 1] += bucket[size_t(v)];

  // Counting sort by lower vertex (linear, unlike a hash map or a comparison sort).
  // Placing advances bucket[lo] to the end of lo's range, which is where lo+1's begins.
  // Threads place in any order; the sort below restores one.
  std::vector<int32_t>& sorted = c.edge_halfedges;
  sorted.resize(size_t(nh));
  for_each_face(mesh, [&](int32_t, int32_t h, int32_t u, int32_t v) {
    const int32_t at = std::atomic_ref<int32_t>(bucket[size_t(std::min(u, v))]).fetch_add(1, std::memory_order_relaxed);
    sorted[size_t(at)] = h;
  });

  // Within a lower vertex's range (about half its valence), order by (upper vertex,
  // halfedge): the halfedges of each edge become contiguous and in increasing order.
  // Each block of vertices counts its edges, then writes them at its offset.
  const int32_t blocks = nv / kVertexBlock + 1;
  std::vector<int32_t> block_edges(size_t(blocks) + 1, 0);
  auto range_start = [&](int32_t lo) { return lo == 0 ? 0 : bucket[size_t(lo) - 1]; };
  auto before = [&](int32_t a, int32_t b) { return upper[size_t(a)] != upper[size_t(b)] ? upper[size_t(a)] < upper[size_t(b)] : a < b; };
  tbb::parallel_for(0, blocks, [&](int32_t block) {
    int32_t edges = 0;
    for (int32_t lo = block * kVertexBlock; lo < std::min(nv, (block + 1) * kVertexBlock); ++lo) {
      int32_t* range = sorted.data() + range_start(lo);
      const int32_t n = bucket[size_t(lo)] - range_start(lo);
      if (n > 32) {
        std::sort(range, range + n, before);
      } else {
        for (int32_t i = 1; i < n; ++i)
          for (int32_t j = i; j > 0 && before(range[j], range[j - 1]); --j) std::swap(range[j], range[j - 1]);
      }
      for (int32_t i = 0; i < n; ++i) edges += i == 0 || upper[size_t(range[i])] != upper[size_t(range[i - 1])];
    }
    block_edges[size_t(block) + 1] = edges;
  });
  for (int32_t b = 0; b < blocks; ++b) block_edges[size_t(b) + 1] += block_edges[size_t(b)];
  const int32_t ne = block_edges.back();
  c.edge_vertices.resize(size_t(ne));
  c.edge_start.resize(size_t(ne) + 1);
  c.edge_start[size_t(ne)] = nh;
  tbb::parallel_for(0, blocks, [&](int32_t block) {
    int32_t e = block_edges[size_t(block)];
    for (int32_t lo = block * kVertexBlock; lo < std::min(nv, (block + 1) * kVertexBlock); ++lo) {
      const int32_t first = range_start(lo), n = bucket[size_t(lo)] - first;
      for (int32_t i = 0; i < n; ++i)
        if (i == 0 || upper[size_t(sorted[size_t(first + i)])] != upper[size_t(sorted[size_t(first + i - 1)])]) {
          c.edge_vertices[size_t(e)] = {lo, upper[size_t(sorted[size_t(first + i)])]};
          c.edge_start[size_t(e)] = first + i;
          ++e;
        }
    }
  });
  // Only now may halfedge_edge stop holding upper vertices.
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, ne, 1 << 14), [&](const tbb::blocked_range<int32_t>& r) {
    for (int32_t e = r.begin(); e < r.end(); ++e)
      for (int32_t i = c.edge_start[size_t(e)]; i < c.edge_start[size_t(e) + 1]; ++i) c.halfedge_edge[size_t(sorted[size_t(i)])] = e;
  });
  return c;
}

} // namespace meander
