#include "meander/locality.h"

#include "chunks.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meander {

namespace {

constexpr int32_t kScatteredFrom = 1 << 18; // faces; below, the arrays mostly fit the caches
// is_scattered's sample: runs of faces, and the blocks of vertex indices their corners
// touch. Measured per run of 1024 faces, blocks of 1024 vertices: 2-3 on generated
// spheres, tori and grids from 300k to 10M triangles, 26-30 on OpenSubdiv's refinements (a
// few streams of vertices, each in order, which run as fast), 147 on a shuffled sphere of
// 300k triangles (all its blocks), 487 at 1M, 573 on a 10M sphere whose vertices are
// sorted by x.
constexpr int32_t kRuns = 64, kRun = 1024;
constexpr int kBlockBits = 10;
constexpr int32_t kScatteredBlocks = 64;
constexpr int kCellBits = 10;  // per axis: a 30-bit Morton code
constexpr int kDigitBits = 10; // per counting pass: three passes

// The 10 low bits of x spread to every third bit.
uint32_t spread_bits(uint32_t x) {
  x &= 0x3ff;
  x = (x | x << 16) & 0x030000ff;
  x = (x | x << 8) & 0x0300f00f;
  x = (x | x << 4) & 0x030c30c3;
  x = (x | x << 2) & 0x09249249;
  return x;
}

// The index of each element under a permutation given as "new element i is old element
// order[i]", for a count of elements.
std::vector<int32_t> inverse(const std::vector<int32_t>& order) {
  std::vector<int32_t> rank(order.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, order.size(), 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) rank[size_t(order[i])] = int32_t(i);
  });
  return rank;
}

// The faces of `mesh` in the order `source` gives (new face i is old face source[i]),
// their corners renamed by vertex_name, and the positions placed by `place` (new
// position i = old position place[i]). Each new face is read from where it was and
// written in order, not read in order and written where it goes: scattered writes miss
// the TLB as often as scattered reads and fetch each line before writing it too, and
// `reordered` needs no inverse of the face order. On the shuffled 10M sphere (perf,
// small pages) the faces and the inverse took 0.43 s of CPU against 0.59 s.
PolygonMesh permuted(const PolygonMesh& mesh, const std::vector<int32_t>& source,
                     const std::vector<int32_t>& vertex_name, const std::vector<int32_t>& place) {
  PolygonMesh out;
  out.positions.resize(mesh.positions.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, place.size(), 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) out.positions[i] = mesh.positions[size_t(place[i])];
  });
  const int32_t nf = mesh.num_faces();
  const int32_t size = nf > 0 ? mesh.face_size(0) : 0;
  const auto faces = tbb::blocked_range<int32_t>(0, nf, 1 << 16);
  out.face_start.resize(size_t(nf) + 1);
  if (int64_t(size) * nf == mesh.num_corners() &&
      std::adjacent_find(mesh.face_start.begin(), mesh.face_start.end(),
                         [&](int32_t a, int32_t b) { return b - a != size; }) == mesh.face_start.end()) {
    out.face_start = mesh.face_start; // all faces of one size: they only swap places
  } else {
    out.face_start[0] = 0;
    tbb::parallel_for(faces, [&](const tbb::blocked_range<int32_t>& r) {
      for (int32_t f = r.begin(); f < r.end(); ++f) out.face_start[size_t(f) + 1] = mesh.face_size(source[size_t(f)]);
    });
    for (int32_t f = 0; f < nf; ++f) out.face_start[size_t(f) + 1] += out.face_start[size_t(f)];
  }
  out.face_vertices.resize(mesh.face_vertices.size());
  tbb::parallel_for(faces, [&](const tbb::blocked_range<int32_t>& r) {
    for (int32_t f = r.begin(); f < r.end(); ++f) {
      int32_t* to = out.face_vertices.data() + out.face_start[size_t(f)];
      for (const int32_t v : mesh.face(source[size_t(f)])) *to++ = vertex_name[size_t(v)];
    }
  });
  return out;
}

// The items 0..n-1 ordered by code(item) (30 bits), ties in item order: three stable
// counting passes over (code, item) pairs, each parallel over chunks.
template <typename Code>
std::vector<int32_t> sorted_by_code(int32_t n, Code&& code) {
  std::vector<uint64_t> keys(static_cast<size_t>(n)), sorted(static_cast<size_t>(n));
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, n, 1 << 16), [&](const tbb::blocked_range<int32_t>& r) {
    for (int32_t i = r.begin(); i < r.end(); ++i) keys[size_t(i)] = uint64_t(code(i)) << 32 | uint32_t(i);
  });
  constexpr int kDigits = 1 << kDigitBits;
  std::vector<std::array<int32_t, kDigits>> count(kChunks);
  for (int shift = 32; shift < 32 + 3 * kCellBits; shift += kDigitBits) {
    const auto digit = [&](uint64_t key) { return size_t(key >> shift) & (kDigits - 1); };
    for_chunks(n, [&](int32_t c, int32_t begin, int32_t end) {
      count[size_t(c)].fill(0);
      for (int32_t i = begin; i < end; ++i) ++count[size_t(c)][digit(keys[size_t(i)])];
    });
    // Each chunk's first place for each digit: digits in order, chunks in order within a
    // digit, which keeps the sort stable.
    int32_t next = 0;
    for (size_t d = 0; d < kDigits; ++d)
      for (int32_t c = 0; c < kChunks; ++c) next += std::exchange(count[size_t(c)][d], next);
    for_chunks(n, [&](int32_t c, int32_t begin, int32_t end) {
      for (int32_t i = begin; i < end; ++i) sorted[size_t(count[size_t(c)][digit(keys[size_t(i)])]++)] = keys[size_t(i)];
    });
    keys.swap(sorted);
  }
  std::vector<int32_t> items(static_cast<size_t>(n));
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, n, 1 << 16), [&](const tbb::blocked_range<int32_t>& r) {
    for (int32_t i = r.begin(); i < r.end(); ++i) items[size_t(i)] = int32_t(uint32_t(keys[size_t(i)]));
  });
  return items;
}

} // namespace

bool is_scattered(const PolygonMesh& mesh) {
  const int32_t nf = mesh.num_faces();
  if (nf < kScatteredFrom) return false;
  // Runs of faces spread evenly over the mesh, the same ones every time.
  std::array<int32_t, kRuns> blocks{};
  tbb::parallel_for(0, kRuns, [&](int32_t run) {
    const int32_t begin = int32_t(int64_t(nf) * run / kRuns), end = std::min(nf, begin + kRun);
    std::vector<int32_t> touched(mesh.face_vertices.begin() + mesh.face_start[size_t(begin)],
                                 mesh.face_vertices.begin() + mesh.face_start[size_t(end)]);
    for (int32_t& v : touched) v >>= kBlockBits; // any index, in range or not
    std::sort(touched.begin(), touched.end());
    blocks[size_t(run)] = int32_t(std::unique(touched.begin(), touched.end()) - touched.begin());
  });
  int64_t total = 0;
  for (const int32_t count : blocks) total += count;
  return total > int64_t(kScatteredBlocks) * kRuns;
}

MeshOrder locality_order(const PolygonMesh& mesh) {
  const int32_t nf = mesh.num_faces(), nv = mesh.num_vertices();
  Box3 box;
  for (const Vec3& p : mesh.positions)
    if (is_finite(p)) box.extend(p);
  const float cells = float(1 << kCellBits);
  const auto cell = [&](float x, float lo, float hi) {
    const float t = hi > lo ? (x - lo) / (hi - lo) * cells : 0.0f;
    return t >= 0 ? uint32_t(std::min(t, cells - 1)) : 0u; // NaN too: repair refuses it later
  };
  const auto code = [&](Vec3 p) {
    return spread_bits(cell(p.x, box.min.x, box.max.x)) | spread_bits(cell(p.y, box.min.y, box.max.y)) << 1 |
           spread_bits(cell(p.z, box.min.z, box.max.z)) << 2;
  };
  MeshOrder order;
  // Vertices by their own codes; a face by its first vertex's, which is where that
  // vertex went.
  std::vector<uint32_t> vertex_code(static_cast<size_t>(nv));
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, nv, 1 << 16), [&](const tbb::blocked_range<int32_t>& r) {
    for (int32_t v = r.begin(); v < r.end(); ++v) vertex_code[size_t(v)] = code(mesh.positions[size_t(v)]);
  });
  const std::vector<int32_t> vertex_order = sorted_by_code(nv, [&](int32_t v) { return vertex_code[size_t(v)]; });
  order.vertex_rank = inverse(vertex_order);
  order.face_order = sorted_by_code(nf, [&](int32_t f) {
    return mesh.face_size(f) > 0 ? vertex_code[size_t(mesh.face(f)[0])] : 0u;
  });
  return order;
}

PolygonMesh reordered(const PolygonMesh& mesh, const MeshOrder& order) {
  return permuted(mesh, order.face_order, order.vertex_rank, inverse(order.vertex_rank));
}

PolygonMesh restored(const PolygonMesh& mesh, const MeshOrder& order) {
  return permuted(mesh, inverse(order.face_order), inverse(order.vertex_rank), order.vertex_rank);
}

} // namespace meander
