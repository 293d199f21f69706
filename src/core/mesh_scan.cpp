#include "mesh_scan.h"

#include "chunks.h"

#include <array>
#include <limits>

namespace meander {

namespace {

// Faces a and b (without repeated vertices) are the same cycle, up to rotation and
// orientation. Called once per manifold edge, so it rejects early and never divides.
bool same_cycle(std::span<const int32_t> a, std::span<const int32_t> b) {
  const size_t n = a.size();
  if (n != b.size()) return false;
  size_t j = size_t(std::find(b.begin(), b.end(), a[0]) - b.begin());
  if (j == n) return false;
  const bool forward = b[j + 1 == n ? 0 : j + 1] == a[1];
  for (size_t i = 1; i < n; ++i) {
    j = forward ? (j + 1 == n ? 0 : j + 1) : (j == 0 ? n - 1 : j - 1);
    if (a[i] != b[j]) return false;
  }
  return true;
}

} // namespace

std::string plural(int64_t n, std::string_view one, std::string_view many) {
  return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

std::string degenerate_reason(int32_t input_face, size_t size, int32_t repeated) {
  return "face " + std::to_string(input_face) +
         (repeated >= 0 ? " repeats vertex " + std::to_string(repeated)
                        : " has only " + plural(int64_t(size), "vertex", "vertices"));
}

FaceCleanup clean_faces(PolygonMesh& m, std::vector<int32_t>& origin) {
  const int32_t nv = m.num_vertices();
  RepeatFinder repeats(nv);
  FaceCleanup result;
  rewrite_faces(m, origin, [&](int32_t f, std::span<const int32_t> face, int32_t* out) -> int32_t {
    if (!all_in_range(face, nv)) return -1;
    const int32_t repeated = repeats(face);
    if (repeated < 0 && face.size() >= 3) return keep_face(face, out);
    int32_t n = 0; // collapsing overwrites `face` as it goes, never ahead of reading it
    for (const int32_t v : face)
      if (n == 0 || out[n - 1] != v) out[n++] = v;
    while (n > 1 && out[n - 1] == out[0]) --n;
    const bool kept = n >= 3 && repeats({out, size_t(n)}) < 0;
    if ((kept ? result.collapsed : result.dropped)++ == 0)
      (kept ? result.first_collapsed : result.first_dropped) = degenerate_reason(origin[size_t(f)], face.size(), repeated);
    return kept ? n : -1;
  });
  return result;
}

bool misoriented(const PolygonMesh& m, const Connectivity& c, int32_t e) {
  if (c.edge_degree(e) != 2) return false;
  const int32_t i = c.edge_start[size_t(e)];
  return m.face_vertices[size_t(c.edge_halfedges[size_t(i)])] ==
         m.face_vertices[size_t(c.edge_halfedges[size_t(i) + 1])];
}

EdgeScan scan_edges(const PolygonMesh& m, const Connectivity& c) {
  EdgeScan s{.fans = UnionFind(m.num_corners())};
  // In parallel over fixed chunks of edges, each counting for itself; the duplicates are
  // listed per chunk and then taken in edge order, as one pass would take them.
  struct Counts {
    int32_t boundary = 0, non_manifold = 0, first_non_manifold = -1, misoriented = 0;
    std::vector<std::pair<int32_t, int32_t>> duplicates; // (face, the face it repeats)
  };
  std::array<Counts, kChunks> counts;
  for_chunks(c.num_edges(), [&](int32_t k, int32_t begin, int32_t end) {
    Counts& n = counts[size_t(k)];
    for (int32_t e = begin; e < end; ++e) {
      const int32_t degree = c.edge_degree(e);
      if (degree != 2) {
        n.boundary += degree == 1;
        if (degree > 2 && n.non_manifold++ == 0) n.first_non_manifold = e;
        continue;
      }
      const int32_t h1 = c.edge_halfedges[size_t(c.edge_start[size_t(e)])];
      const int32_t h2 = c.edge_halfedges[size_t(c.edge_start[size_t(e)]) + 1];
      const int32_t n1 = next_halfedge(m, c, h1), n2 = next_halfedge(m, c, h2);
      if (m.face_vertices[size_t(h1)] == m.face_vertices[size_t(h2)]) { // both leave the same vertex
        ++n.misoriented;
        s.fans.unite_concurrently(h1, h2);
        s.fans.unite_concurrently(n1, n2);
      } else {
        s.fans.unite_concurrently(h1, n2);
        s.fans.unite_concurrently(n1, h2);
      }
      // Faces that repeat each other share every edge, so where they share a manifold edge
      // no third face can repeat them.
      const int32_t f1 = c.face_of(h1), f2 = c.face_of(h2);
      if (same_cycle(m.face(f1), m.face(f2))) n.duplicates.emplace_back(f2, f1);
    }
  });
  std::vector<int32_t> duplicate_of; // per face; allocated at the first duplicate
  const auto found = [&](int32_t f, int32_t earlier) {
    if (duplicate_of.empty()) duplicate_of.assign(size_t(m.num_faces()), -1);
    duplicate_of[size_t(f)] = earlier;
  };
  for (const Counts& n : counts) {
    s.boundary += n.boundary;
    s.misoriented += n.misoriented;
    if (n.non_manifold > 0 && s.non_manifold == 0) s.first_non_manifold = n.first_non_manifold;
    s.non_manifold += n.non_manifold;
    for (const auto& [f, earlier] : n.duplicates) found(f, earlier);
  }
  // Faces with only non-manifold edges: compare with the faces before them on their least
  // shared edge (listed in increasing order, so the first match is the first face).
  for (int32_t f = 0; f < m.num_faces() && s.non_manifold > 0; ++f) {
    int32_t edge = -1, degree = std::numeric_limits<int32_t>::max();
    for (int32_t h = m.face_start[size_t(f)]; h < m.face_start[size_t(f) + 1] && degree > 2; ++h)
      if (const int32_t e = c.halfedge_edge[size_t(h)]; c.edge_degree(e) < degree) {
        edge = e;
        degree = c.edge_degree(e);
      }
    if (degree <= 2) continue;
    for (const int32_t h : c.halfedges(edge)) {
      const int32_t g = c.face_of(h);
      if (g >= f) break;
      if (same_cycle(m.face(f), m.face(g))) {
        found(f, g);
        break;
      }
    }
  }
  for (int32_t f = 0; f < int32_t(duplicate_of.size()); ++f)
    if (duplicate_of[size_t(f)] >= 0) s.duplicates.emplace_back(f, duplicate_of[size_t(f)]);
  return s;
}

std::vector<int32_t> count_fans(const PolygonMesh& m, const UnionFind& fans) {
  std::vector<int32_t> count(size_t(m.num_vertices()), 0);
  for (int32_t h = 0; h < m.num_corners(); ++h)
    if (fans.is_root(h)) ++count[size_t(m.face_vertices[size_t(h)])];
  return count;
}

// Union-find over the edges in mesh order: a breadth-first search over the faces jumps
// around memory and took 4 s on 10M triangles.
Sheets find_sheets(const PolygonMesh& m, const Connectivity& c) {
  const int32_t nf = m.num_faces();
  ParityUnionFind windings(nf);
  std::vector<uint8_t> odd_cycle(size_t(nf), 0); // a face closing a cycle that reverses winding
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    if (c.edge_degree(e) != 2) continue;
    const int32_t h1 = c.halfedges(e)[0], h2 = c.halfedges(e)[1];
    const int32_t f1 = c.face_of(h1), f2 = c.face_of(h2);
    if (!windings.unite(f1, f2, uint8_t(m.face_vertices[size_t(h1)] != m.face_vertices[size_t(h2)] ? 0 : 1)))
      odd_cycle[size_t(f1)] = 1;
  }
  Sheets s;
  s.sheet.resize(size_t(nf));
  s.flipped.resize(size_t(nf));
  std::vector<int32_t> sheet_of_root(size_t(nf), -1);
  std::vector<uint8_t> first_parity;
  for (int32_t f = 0; f < nf; ++f) {
    const auto [root, parity] = windings.find(f);
    int32_t& id = sheet_of_root[size_t(root)];
    if (id < 0) {
      id = s.size();
      s.faces.push_back(0);
      s.orientable.push_back(1);
      first_parity.push_back(parity);
    }
    s.sheet[size_t(f)] = id;
    s.flipped[size_t(f)] = parity ^ first_parity[size_t(id)];
    ++s.faces[size_t(id)];
    if (odd_cycle[size_t(f)]) s.orientable[size_t(id)] = 0;
  }
  return s;
}

} // namespace meander
