#include "meander/connectivity.h"

#include <algorithm>
#include <tuple>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

namespace meander {

namespace {

// Fixed blocks of vertices, so that the edge numbering does not depend on how the
// threads share the work.
constexpr int32_t kVertexBlock = 1 << 15;
// Chunks of faces counted apart: each needs a count per vertex.
constexpr int32_t kMaxChunks = 8;

} // namespace

Connectivity build_connectivity(const PolygonMesh& mesh) {
  const int32_t nv = mesh.num_vertices();
  const int32_t nh = mesh.num_corners();
  Connectivity c;
  const int32_t nf = mesh.num_faces();
  c.face_size = nf > 0 ? mesh.face_size(0) : 0;
  c.face_size = tbb::parallel_reduce(
      tbb::blocked_range<int32_t>(0, nf, 1 << 16), c.face_size,
      [&](const tbb::blocked_range<int32_t>& r, int32_t size) {
        for (int32_t f = r.begin(); f < r.end() && size > 0; ++f) size = mesh.face_size(f) == size ? size : 0;
        return size;
      },
      [](int32_t a, int32_t b) { return a == b ? a : 0; });
  if (c.face_size == 0) c.halfedge_face.resize(size_t(nh));
  // Counting sort by lower vertex (linear, unlike a hash map or a comparison sort), in
  // a few fixed chunks of faces with a count per chunk and vertex: no atomic operations,
  // which cost more than the counting. The sort below restores one order whatever the
  // chunks. Each halfedge is placed with its upper vertex beside it, so that the sorts
  // and scans below read their keys in order instead of gathering them from all over a
  // halfedge-indexed array; the keys live in halfedge_edge's memory until the edges are
  // numbered (fresh pages cost more than the work).
  const int32_t chunks = std::clamp(tbb::this_task_arena::max_concurrency(), 1, kMaxChunks);
  auto chunk_faces = [&](int32_t k) { return int32_t(int64_t(nf) * k / chunks); };
  // place[lo * chunks + k]: where chunk k puts its next halfedge of lower vertex lo.
  std::vector<int32_t> place(size_t(nv) * size_t(chunks), 0);
  auto for_each_chunk = [&](auto&& body) {
    tbb::parallel_for(0, chunks, [&](int32_t k) {
      for (int32_t f = chunk_faces(k); f < chunk_faces(k + 1); ++f) {
        const int32_t b = mesh.face_start[f], e = mesh.face_start[f + 1];
        for (int32_t h = b; h < e; ++h) {
          const int32_t u = mesh.face_vertices[size_t(h)], v = mesh.face_vertices[size_t(h + 1 == e ? b : h + 1)];
          body(f, h, u, v, place[size_t(std::min(u, v)) * size_t(chunks) + size_t(k)]);
        }
      }
    }, tbb::static_partitioner());
  };
  for_each_chunk([&](int32_t f, int32_t h, int32_t, int32_t, int32_t& count) {
    if (c.face_size == 0) c.halfedge_face[size_t(h)] = f;
    ++count;
  });
  // range[lo] .. range[lo + 1]: the halfedges of lower vertex lo once placed.
  std::vector<int32_t> range(size_t(nv) + 1);
  int32_t placed = 0;
  for (size_t lo = 0; lo < size_t(nv); ++lo) {
    range[lo] = placed;
    for (size_t k = 0; k < size_t(chunks); ++k) placed += std::exchange(place[lo * size_t(chunks) + k], placed);
  }
  range[size_t(nv)] = placed;
  UninitVector<int32_t>& sorted = c.edge_halfedges;
  UninitVector<int32_t>& upper = c.halfedge_edge;
  sorted.resize(size_t(nh));
  upper.resize(size_t(nh));
  for_each_chunk([&](int32_t, int32_t h, int32_t u, int32_t v, int32_t& at) {
    sorted[size_t(at)] = h;
    upper[size_t(at)] = std::max(u, v);
    ++at;
  });
  std::vector<int32_t>().swap(place);

  // Within a lower vertex's range (about half its valence), order by (upper vertex,
  // halfedge): the halfedges of each edge become contiguous and in increasing order.
  // Chunk k's faces come before chunk k+1's and each chunk places its halfedges in
  // increasing order, so a range is already in increasing halfedge order and a stable
  // sort by the upper vertex alone is enough. Each block of vertices counts its edges,
  // then writes them at its offset.
  const int32_t blocks = nv / kVertexBlock + 1;
  std::vector<int32_t> block_edges(size_t(blocks) + 1, 0);
  tbb::parallel_for(0, blocks, [&](int32_t block) {
    int32_t edges = 0;
    std::vector<std::pair<int32_t, int32_t>> large;
    for (int32_t lo = block * kVertexBlock; lo < std::min(nv, (block + 1) * kVertexBlock); ++lo) {
      const int32_t first = range[size_t(lo)], n = range[size_t(lo) + 1] - first;
      int32_t* key = upper.data() + first;
      int32_t* h = sorted.data() + first;
      if (n > 32) {
        large.resize(size_t(n));
        for (int32_t i = 0; i < n; ++i) large[size_t(i)] = {key[i], h[i]};
        std::sort(large.begin(), large.end());
        for (int32_t i = 0; i < n; ++i) std::tie(key[i], h[i]) = large[size_t(i)];
      } else {
        for (int32_t i = 1; i < n; ++i) {
          const int32_t k = key[i], hi = h[i];
          int32_t j = i;
          for (; j > 0 && key[j - 1] > k; --j) {
            key[j] = key[j - 1];
            h[j] = h[j - 1];
          }
          key[j] = k;
          h[j] = hi;
        }
      }
      for (int32_t i = 0; i < n; ++i) edges += i == 0 || key[i] != key[i - 1];
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
      const int32_t first = range[size_t(lo)], n = range[size_t(lo) + 1] - first;
      for (int32_t i = first; i < first + n; ++i)
        if (i == first || upper[size_t(i)] != upper[size_t(i - 1)]) {
          c.edge_vertices[size_t(e)] = {lo, upper[size_t(i)]};
          c.edge_start[size_t(e)] = i;
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
