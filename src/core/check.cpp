#include "meander/check.h"

#include "meander/connectivity.h"
#include "meander/error.h"
#include "meander/locality.h"
#include "chunks.h"
#include "union_find.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <limits>
#include <numeric>
#include <span>
#include <utility>

#include <tbb/enumerable_thread_specific.h>

namespace meander {

namespace {

// Faces up to this size are searched for a repeated vertex pairwise: cheaper than a
// per-vertex stamp array for the triangles and quads that make up nearly every mesh.
constexpr size_t kPairwiseRepeatSearch = 8;

// Relative to the squared bounding-box diagonal. Float coordinates resolve about 1e-7 of
// the model's size, so a face whose area is below (1e-6 diagonal)^2 has no shape that
// the file can express; exactly collinear vertices give ~1e-16 after rounding.
constexpr double kZeroAreaRelative = 1e-12;

std::string plural(int64_t n, std::string_view one, std::string_view many) {
  return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

std::string edge_name(const std::array<int32_t, 2>& edge) {
  char text[32];
  std::snprintf(text, sizeof text, "(%d,%d)", edge[0], edge[1]);
  return text;
}

std::string point_name(Vec3 p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", double(p.x), double(p.y), double(p.z));
  return text;
}

bool in_range(int32_t v, int32_t num_vertices) { return uint32_t(v) < uint32_t(num_vertices); }

bool all_in_range(std::span<const int32_t> face, int32_t num_vertices) {
  return std::all_of(face.begin(), face.end(), [&](int32_t v) { return in_range(v, num_vertices); });
}

// Finds a vertex that occurs twice in a face, in time linear in the face size whatever
// the size. The faces must index in range.
class RepeatFinder {
public:
  explicit RepeatFinder(int32_t num_vertices) : num_vertices_(num_vertices) {}

  // The vertex whose second occurrence comes first, or -1.
  int32_t operator()(std::span<const int32_t> face) {
    if (face.size() <= kPairwiseRepeatSearch) {
      for (size_t j = 1; j < face.size(); ++j)
        for (size_t i = 0; i < j; ++i)
          if (face[i] == face[j]) return face[j];
      return -1;
    }
    if (stamp_.empty()) stamp_.assign(size_t(num_vertices_), -1);
    ++round_; // a fresh mark per face, so the array is never cleared
    for (const int32_t v : face) {
      if (stamp_[size_t(v)] == round_) return v;
      stamp_[size_t(v)] = round_;
    }
    return -1;
  }

private:
  int32_t num_vertices_;
  int32_t round_ = -1;
  std::vector<int32_t> stamp_;
};

// Why face `input_face` (of `size` vertices as given, `repeated` what RepeatFinder said)
// is not a polygon.
std::string degenerate_reason(int32_t input_face, size_t size, int32_t repeated) {
  return "face " + std::to_string(input_face) +
         (repeated >= 0 ? " repeats vertex " + std::to_string(repeated)
                        : " has only " + plural(int64_t(size), "vertex", "vertices"));
}

// Rewrites the faces of `m` in place and in order: `rewrite(f, face, out)` writes the new
// vertices of face f to `out`, which never lies after face.data() (writing can only stay
// behind reading), and returns how many it wrote, or -1 to drop the face. `origin` maps
// each face to a face of the input (empty: the identity) and follows the faces.
template <typename Rewrite>
void rewrite_faces(PolygonMesh& m, std::vector<int32_t>& origin, Rewrite&& rewrite) {
  const int32_t nf = m.num_faces();
  if (origin.empty()) {
    origin.resize(size_t(nf));
    std::iota(origin.begin(), origin.end(), 0);
  }
  int32_t begin = 0, written = 0, kept = 0;
  for (int32_t f = 0; f < nf; ++f) {
    const int32_t end = m.face_start[size_t(f) + 1];
    const std::span<const int32_t> face(m.face_vertices.data() + begin, size_t(end - begin));
    const int32_t n = rewrite(f, face, m.face_vertices.data() + written);
    begin = end;
    if (n < 0) continue;
    written += n;
    origin[size_t(kept)] = origin[size_t(f)];
    m.face_start[size_t(++kept)] = written;
  }
  m.face_start.resize(size_t(kept) + 1);
  m.face_vertices.resize(size_t(written));
  origin.resize(size_t(kept));
}

// The rewrite that keeps a face as it is.
int32_t keep_face(std::span<const int32_t> face, int32_t* out) {
  if (out != face.data()) std::copy(face.begin(), face.end(), out); // out lies before face: a forward copy is safe
  return int32_t(face.size());
}

struct FaceCleanup {
  int32_t collapsed = 0; // kept once repeated consecutive vertices were collapsed
  int32_t dropped = 0;   // fewer than 3 vertices, or a vertex repeated, after collapsing
  std::string first_collapsed, first_dropped;
};

// Repair step 2. Faces with an index out of range are dropped silently: repair refused
// them before, and inspect counts them apart but keeps them out of the topology.
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

// A manifold edge whose two faces both run from the same vertex to the other.
bool misoriented(const PolygonMesh& m, const Connectivity& c, int32_t e) {
  if (c.edge_degree(e) != 2) return false;
  const int32_t i = c.edge_start[size_t(e)];
  return m.face_vertices[size_t(c.edge_halfedges[size_t(i)])] ==
         m.face_vertices[size_t(c.edge_halfedges[size_t(i) + 1])];
}

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

// What one pass over the edges finds, in faces that are polygons with indices in range.
// The checks share the pass because on a clean mesh it is most of what repair costs
// beyond building the connectivity.
struct EdgeScan {
  int32_t boundary = 0, non_manifold = 0, first_non_manifold = -1, misoriented = 0;
  // Corners (corner h is where halfedge h starts) joined when they are the corners at one
  // vertex of the two faces of a manifold edge: each set is a fan.
  UnionFind fans;
  // Each face that repeats an earlier one, with the first face it repeats, by face.
  std::vector<std::pair<int32_t, int32_t>> duplicates;
};

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

// Number of fans at each vertex.
std::vector<int32_t> count_fans(const PolygonMesh& m, const UnionFind& fans) {
  std::vector<int32_t> count(size_t(m.num_vertices()), 0);
  for (int32_t h = 0; h < m.num_corners(); ++h)
    if (fans.is_root(h)) ++count[size_t(m.face_vertices[size_t(h)])];
  return count;
}

// Gives every fan of a vertex but the first (the one holding its first corner) a copy of
// the vertex, appended in the order the fans are met.
void split_fans(PolygonMesh& m, UnionFind& corners, const std::vector<int32_t>& fans) {
  std::vector<int32_t> first_fan(size_t(m.num_vertices()), -1), copy(size_t(m.num_corners()), -1);
  for (int32_t h = 0; h < m.num_corners(); ++h) {
    const int32_t v = m.face_vertices[size_t(h)];
    if (fans[size_t(v)] < 2) continue;
    const int32_t fan = corners.find(h);
    if (first_fan[size_t(v)] < 0) first_fan[size_t(v)] = fan;
    if (fan == first_fan[size_t(v)]) continue;
    if (copy[size_t(fan)] < 0) {
      copy[size_t(fan)] = m.num_vertices();
      const Vec3 p = m.positions[size_t(v)];
      m.positions.push_back(p);
    }
    m.face_vertices[size_t(h)] = copy[size_t(fan)];
  }
}

// Union-find whose elements carry a parity relative to their root (path halving, union
// by size, as UnionFind): here, whether a face is wound against the root of its sheet.
class ParityUnionFind {
public:
  explicit ParityUnionFind(int32_t n) : parent_(size_t(n), -1), parity_(size_t(n), 0) {}

  // The root of x, and x's parity relative to it.
  std::pair<int32_t, uint8_t> find(int32_t x) {
    uint8_t parity = 0;
    for (int32_t p; (p = parent_[size_t(x)]) >= 0;) {
      const int32_t grandparent = parent_[size_t(p)];
      if (grandparent < 0) return {p, uint8_t(parity ^ parity_[size_t(x)])};
      parity_[size_t(x)] ^= parity_[size_t(p)]; // x hangs from its grandparent now
      parent_[size_t(x)] = grandparent;
      parity ^= parity_[size_t(x)];
      x = grandparent;
    }
    return {x, parity};
  }

  // Records that a and b differ in parity iff `odd`; false if that contradicts what was
  // recorded before.
  bool unite(int32_t a, int32_t b, uint8_t odd) {
    auto [ra, pa] = find(a);
    auto [rb, pb] = find(b);
    if (ra == rb) return (pa ^ pb) == odd;
    if (parent_[size_t(ra)] > parent_[size_t(rb)]) std::swap(ra, rb); // ra's set is the larger
    parent_[size_t(ra)] += parent_[size_t(rb)];
    parent_[size_t(rb)] = ra;
    parity_[size_t(rb)] = pa ^ pb ^ odd;
    return true;
  }

private:
  std::vector<int32_t> parent_; // as in UnionFind: minus the set's size at a root
  std::vector<uint8_t> parity_; // relative to the parent
};

// Faces joined across manifold edges ("sheets"), each face with its winding relative to
// its sheet's first face. Union-find over the edges in mesh order: a breadth-first search
// over the faces jumps around memory and took 4 s on 10M triangles.
struct Sheets {
  std::vector<int32_t> sheet;      // per face; sheets are numbered by their first face
  std::vector<uint8_t> flipped;    // per face: wound against its sheet's first face
  std::vector<int32_t> faces;      // per sheet
  std::vector<uint8_t> orientable; // per sheet
  int32_t size() const { return int32_t(faces.size()); }
};

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

// Reverses face f, keeping its first vertex first.
void reverse_face(PolygonMesh& m, int32_t f) {
  std::reverse(m.face_vertices.begin() + m.face_start[size_t(f)] + 1, m.face_vertices.begin() + m.face_start[size_t(f) + 1]);
}

std::vector<uint8_t> referenced(const PolygonMesh& m) {
  std::vector<uint8_t> used(size_t(m.num_vertices()), 0);
  for (const int32_t v : m.face_vertices) used[size_t(v)] = 1;
  return used;
}

// Repair step 1 (every index in range and every used position finite, or a refusal),
// and the search for step 2's first face, in one pass over the faces.
struct FaceScan {
  std::vector<uint8_t> used; // per vertex
  int32_t first_degenerate = -1, repeated = -1; // a face with < 3 vertices or a repeat, and the vertex
};

FaceScan scan_faces(const PolygonMesh& m, const std::string& prefix) {
  const int32_t nv = m.num_vertices(), nf = m.num_faces();
  FaceScan s;
  s.used.assign(size_t(nv), 0);
  // In parallel over fixed chunks of faces, each finding its own first bad face; the
  // first chunk's that has one is the first face.
  struct First {
    int32_t out_of_range = -1, degenerate = -1, repeated = -1;
  };
  std::array<First, kChunks> first;
  tbb::enumerable_thread_specific<RepeatFinder> finders([nv] { return RepeatFinder(nv); });
  for_chunks(nf, [&](int32_t k, int32_t begin, int32_t end) {
    First& found = first[size_t(k)];
    RepeatFinder& repeats = finders.local();
    for (int32_t f = begin; f < end; ++f) {
      const std::span<const int32_t> face = m.face(f);
      if (!all_in_range(face, nv)) {
        found.out_of_range = f;
        return;
      }
      for (const int32_t v : face) std::atomic_ref<uint8_t>(s.used[size_t(v)]).store(1, std::memory_order_relaxed);
      if (found.degenerate < 0) {
        const int32_t repeated = repeats(face);
        if (repeated >= 0 || face.size() < 3) {
          found.degenerate = f;
          found.repeated = repeated;
        }
      }
    }
  });
  for (const First& found : first) {
    if (const int32_t f = found.out_of_range; f >= 0) {
      const int32_t v = *std::find_if(m.face(f).begin(), m.face(f).end(), [&](int32_t u) { return !in_range(u, nv); });
      throw TopologyError(prefix + "face " + std::to_string(f) + " references vertex " + std::to_string(v) +
                          " but the mesh has " + plural(nv, "vertex", "vertices"));
    }
    if (found.degenerate >= 0 && s.first_degenerate < 0) {
      s.first_degenerate = found.degenerate;
      s.repeated = found.repeated;
    }
  }
  for (int32_t v = 0; v < nv; ++v)
    if (s.used[size_t(v)] && !is_finite(m.positions[size_t(v)]))
      throw InputError(prefix + "vertex " + std::to_string(v) + " has a non-finite position " +
                       point_name(m.positions[size_t(v)]));
  return s;
}

// Twice the vector area of a face, in double.
double doubled_area(const PolygonMesh& m, std::span<const int32_t> face) {
  const Vec3 p0 = m.positions[size_t(face[0])];
  double x = 0, y = 0, z = 0;
  for (size_t i = 1; i + 1 < face.size(); ++i) {
    const Vec3 a = m.positions[size_t(face[i])], b = m.positions[size_t(face[i + 1])];
    const double ax = double(a.x) - p0.x, ay = double(a.y) - p0.y, az = double(a.z) - p0.z;
    const double bx = double(b.x) - p0.x, by = double(b.y) - p0.y, bz = double(b.z) - p0.z;
    x += ay * bz - az * by;
    y += az * bx - ax * bz;
    z += ax * by - ay * bx;
  }
  return std::sqrt(x * x + y * y + z * z);
}

// Makes each boundary loop one set of `corners` (EdgeScan::fans): a boundary edge
// joins the fans at its two ends, and a fan the two boundary edges that end it. Where a
// fan ends at a non-manifold edge instead, the boundary has no single way on: the fans
// at that vertex left with one boundary end are joined, as one walk along the boundary
// would pass from one to the next.
void join_boundary_loops(const PolygonMesh& m, const Connectivity& c, UnionFind& corners, bool non_manifold_edges) {
  if (non_manifold_edges) {
    std::vector<uint8_t> ends(size_t(m.num_corners()), 0); // boundary edges ending each fan (2 is plenty)
    const auto for_each_boundary_corner = [&](auto&& visit) {
      for (int32_t e = 0; e < c.num_edges(); ++e)
        if (c.edge_degree(e) == 1) {
          const int32_t h = c.halfedges(e)[0];
          visit(h);
          visit(next_halfedge(m, c, h));
        }
    };
    for_each_boundary_corner([&](int32_t h) {
      uint8_t& n = ends[size_t(corners.find(h))];
      n = uint8_t(std::min(n + 1, 2));
    });
    std::vector<int32_t> open_fan(size_t(m.num_vertices()), -1); // a fan at the vertex with one boundary end
    for_each_boundary_corner([&](int32_t h) {
      if (ends[size_t(corners.find(h))] != 1) return;
      int32_t& first = open_fan[size_t(m.face_vertices[size_t(h)])];
      if (first < 0) first = h;
      else corners.unite(first, h);
    });
  }
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_degree(e) == 1) {
      const int32_t h = c.halfedges(e)[0];
      corners.unite(h, next_halfedge(m, c, h));
    }
}

// The topology part of inspect() on faces that are all polygons with indices in range.
void inspect_topology(const PolygonMesh& m, MeshReport& report) {
  const Connectivity c = build_connectivity(m);
  EdgeScan edges = scan_edges(m, c);
  report.edges = c.num_edges();
  report.boundary_edges = edges.boundary;
  report.non_manifold_edges = edges.non_manifold;
  report.misoriented_edges = edges.misoriented;
  report.duplicate_faces = int32_t(edges.duplicates.size());

  // Components: sheets joined across non-manifold edges, numbered by their first face
  // (sheets are numbered that way already).
  const Sheets sheets = find_sheets(m, c);
  const auto sheet_of_halfedge = [&](int32_t h) { return sheets.sheet[size_t(c.face_of(h))]; };
  UnionFind glued(sheets.size());
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_degree(e) > 2)
      for (const int32_t h : c.halfedges(e)) glued.unite(sheet_of_halfedge(c.halfedges(e)[0]), sheet_of_halfedge(h));
  std::vector<int32_t> component_of_sheet(size_t(sheets.size())), number(size_t(sheets.size()), -1);
  for (int32_t s = 0; s < sheets.size(); ++s) {
    int32_t& n = number[size_t(glued.find(s))];
    if (n < 0) {
      n = int32_t(report.components.size());
      report.components.emplace_back();
    }
    component_of_sheet[size_t(s)] = n;
  }
  std::vector<ComponentReport>& components = report.components;
  const auto component = [&](int32_t f) -> ComponentReport& {
    return components[size_t(component_of_sheet[size_t(sheets.sheet[size_t(f)])])];
  };
  for (int32_t s = 0; s < sheets.size(); ++s)
    if (!sheets.orientable[size_t(s)]) components[size_t(component_of_sheet[size_t(s)])].orientable = false;
  report.face_components.resize(size_t(m.num_faces()));
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    const int32_t k = component_of_sheet[size_t(sheets.sheet[size_t(f)])];
    report.face_components[size_t(f)] = k;
    ++components[size_t(k)].faces;
  }
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    ComponentReport& k = component(c.face_of(c.halfedges(e)[0]));
    ++k.edges;
    k.misoriented_edges += misoriented(m, c, e);
    if (c.edge_degree(e) > 2) k.manifold = false;
  }

  // A vertex counts once per component: a manifold vertex is one fan, so in one
  // component; the few fans of non-manifold vertices are sorted out apart.
  UnionFind& corners = edges.fans;
  const std::vector<int32_t> fans = count_fans(m, corners);
  std::vector<std::pair<int32_t, int32_t>> shared; // (vertex, component) of each fan of a non-manifold vertex
  for (int32_t h = 0; h < m.num_corners(); ++h) {
    if (!corners.is_root(h)) continue;
    const int32_t v = m.face_vertices[size_t(h)];
    ComponentReport& k = component(c.face_of(h));
    if (fans[size_t(v)] == 1) {
      ++k.vertices;
    } else {
      k.manifold = false;
      shared.emplace_back(v, int32_t(&k - components.data()));
    }
  }
  std::sort(shared.begin(), shared.end());
  shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
  for (const auto& [v, k] : shared) ++components[size_t(k)].vertices;
  for (const int32_t n : fans) report.non_manifold_vertices += n > 1;

  join_boundary_loops(m, c, corners, report.non_manifold_edges > 0);
  std::vector<bool> counted(size_t(m.num_corners()), false);
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_degree(e) == 1) {
      const int32_t h = c.halfedges(e)[0];
      const int32_t loop = corners.find(h);
      if (counted[size_t(loop)]) continue;
      counted[size_t(loop)] = true;
      ++report.boundary_loops;
      ++component(c.face_of(h)).boundary_loops;
    }

  for (ComponentReport& k : components) {
    k.euler_characteristic = int64_t(k.vertices) - k.edges + k.faces;
    const int64_t deficit = 2 - k.euler_characteristic - k.boundary_loops;
    if (k.manifold) k.genus = int32_t(k.orientable ? deficit / 2 : deficit);
    report.orientable = report.orientable && k.orientable;
  }
}

} // namespace

MeshReport inspect(const PolygonMesh& mesh) {
  const int32_t nv = mesh.num_vertices(), nf = mesh.num_faces();
  MeshReport report;
  report.vertices = nv;
  report.faces = nf;

  std::vector<uint8_t> used(size_t(nv), 0);
  std::vector<int32_t> by_size;
  RepeatFinder repeats(nv);
  bool all_polygons = true; // every face goes into the topology as it is
  for (int32_t f = 0; f < nf; ++f) {
    const std::span<const int32_t> face = mesh.face(f);
    if (face.size() >= by_size.size()) by_size.resize(face.size() + 1, 0);
    ++by_size[face.size()];
    const auto bad = std::count_if(face.begin(), face.end(), [&](int32_t v) { return !in_range(v, nv); });
    if (bad > 0) {
      report.out_of_range_indices += int32_t(bad);
      all_polygons = false;
      continue;
    }
    for (const int32_t v : face) used[size_t(v)] = 1;
    if (face.size() < 3 || repeats(face) >= 0) {
      ++report.degenerate_faces;
      all_polygons = false;
    }
  }
  for (size_t n = 0; n < by_size.size(); ++n)
    if (by_size[n] > 0) report.faces_by_size[int32_t(n)] = by_size[n];
  for (int32_t v = 0; v < nv; ++v) {
    const Vec3 p = mesh.positions[size_t(v)];
    const bool finite = is_finite(p);
    report.non_finite_positions += !finite;
    report.unreferenced_vertices += !used[size_t(v)];
    if (used[size_t(v)] && finite) report.bounding_box.extend(p);
  }

  const double diagonal = report.bounding_box.diagonal();
  const double zero_area = 2 * kZeroAreaRelative * diagonal * diagonal;
  for (int32_t f = 0; f < nf; ++f) {
    const std::span<const int32_t> face = mesh.face(f);
    if (face.size() < 3 || !all_in_range(face, nv) || repeats(face) >= 0) continue;
    if (!std::all_of(face.begin(), face.end(), [&](int32_t v) { return is_finite(mesh.positions[size_t(v)]); })) continue;
    report.zero_area_faces += doubled_area(mesh, face) < zero_area;
  }

  if (all_polygons) {
    inspect_topology(mesh, report);
  } else {
    PolygonMesh polygons = mesh;
    std::vector<int32_t> origin;
    clean_faces(polygons, origin);
    inspect_topology(polygons, report);
    // Back to the input's face numbers.
    std::vector<int32_t> face_components(size_t(nf), -1);
    for (size_t f = 0; f < origin.size(); ++f) face_components[size_t(origin[f])] = report.face_components[f];
    report.face_components = std::move(face_components);
  }
  return report;
}

RepairResult repair(const PolygonMesh& mesh, std::string_view name, const RepairOptions& options) {
  return repair(PolygonMesh(mesh), name, options);
}

namespace {

// repair(), the mesh left in its order: `m` is repaired in place and moved into the
// result. Strict, it is left as it was when a problem is refused.
RepairResult repair_in_order(PolygonMesh& m, const std::string& prefix, const RepairOptions& options) {
  const auto refuse = [&](const std::string& problem) { throw TopologyError(prefix + problem); };
  RepairResult result;
  std::vector<std::string>& repairs = result.repairs;

  // 1. What cannot be repaired.
  FaceScan scan = scan_faces(m, prefix);
  std::vector<uint8_t>& used = scan.used;
  const int32_t input_faces = m.num_faces();
  std::vector<int32_t> origin; // the input face of each face of m; empty while they are the same
  const auto input_face = [&](int32_t f) { return origin.empty() ? f : origin[size_t(f)]; };

  // 2. Repeated vertices.
  if (const int32_t f = scan.first_degenerate; f >= 0) {
    if (options.strict) refuse(degenerate_reason(f, size_t(m.face_size(f)), scan.repeated));
    const FaceCleanup fix = clean_faces(m, origin);
    if (fix.collapsed > 0)
      repairs.push_back("collapsed repeated consecutive vertices in " + plural(fix.collapsed, "face", "faces") + " (" +
                        fix.first_collapsed + ")");
    if (fix.dropped > 0)
      repairs.push_back("dropped " + plural(fix.dropped, "degenerate face", "degenerate faces") + " (" +
                        fix.first_dropped + ")");
    used = referenced(m);
  }

  // 3. Duplicate faces.
  Connectivity c = build_connectivity(m);
  EdgeScan edges = scan_edges(m, c);
  // The two again, once faces changed. The old ones go first: they are as large as the
  // new ones (540 and 120 MB on 10M triangles), and both at once were the run's peak.
  const auto rebuild = [&] {
    c = Connectivity();
    edges.fans = UnionFind(0);
    c = build_connectivity(m);
    edges = scan_edges(m, c);
  };
  if (const auto duplicates = std::move(edges.duplicates); !duplicates.empty()) {
    const std::string example = "face " + std::to_string(input_face(duplicates[0].first)) + " duplicates face " +
                                std::to_string(input_face(duplicates[0].second));
    if (options.strict) refuse(example);
    size_t next = 0;
    rewrite_faces(m, origin, [&](int32_t f, std::span<const int32_t> face, int32_t* out) -> int32_t {
      if (next < duplicates.size() && duplicates[next].first == f) return ++next, -1;
      return keep_face(face, out);
    });
    repairs.push_back("dropped " + plural(int64_t(duplicates.size()), "duplicate face", "duplicate faces") + " (" +
                      example + ")");
    used = referenced(m);
    rebuild();
  }
  if (m.num_faces() == 0)
    throw TopologyError(prefix + "no faces left after repair (" +
                        (input_faces == 0 ? std::string("the mesh has no faces")
                                          : "all " + plural(input_faces, "face was", "faces were") +
                                                " degenerate or duplicates") +
                        ")");

  // 4. Non-manifold edges and vertices. Splitting each vertex into its fans also cuts the
  // edges, since the faces of a fan never cross a non-manifold edge.
  {
    const int32_t cut = edges.non_manifold, first_cut = edges.first_non_manifold;
    if (cut > 0 && options.strict)
      refuse("edge " + edge_name(c.edge_vertices[size_t(first_cut)]) + " is shared by " +
             std::to_string(c.edge_degree(first_cut)) + " faces: mesh is not manifold");
    const std::vector<int32_t> fans = count_fans(m, edges.fans);
    int32_t split = 0, copies = 0, first_split = -1;
    for (int32_t v = 0; v < m.num_vertices(); ++v)
      if (fans[size_t(v)] > 1) {
        if (split++ == 0) first_split = v;
        copies += fans[size_t(v)];
      }
    if (split > 0) {
      const int32_t first_fans = fans[size_t(first_split)];
      if (options.strict)
        refuse("vertex " + std::to_string(first_split) + " joins " + std::to_string(first_fans) +
               " separate fans of faces: mesh is not manifold");
      if (cut > 0) // a non-manifold edge always ends at a split vertex: at least two fans end on it
        repairs.push_back("cut " + plural(cut, "non-manifold edge", "non-manifold edges") + " (edge " +
                          edge_name(c.edge_vertices[size_t(first_cut)]) + " was shared by " +
                          std::to_string(c.edge_degree(first_cut)) + " faces)");
      split_fans(m, edges.fans, fans);
      repairs.push_back("split " + plural(split, "non-manifold vertex", "non-manifold vertices") + " into " +
                        std::to_string(copies) + " copies (vertex " + std::to_string(first_split) + " had " +
                        std::to_string(first_fans) + " fans)");
      used.resize(size_t(m.num_vertices()), 1);
      rebuild();
    }
  }

  // 5. Orientation. A consistently oriented mesh (the usual case) has no misoriented edge
  // and needs no search.
  bool reoriented = false;
  if (edges.misoriented > 0) {
    const Sheets sheets = find_sheets(m, c);
    if (options.strict)
      for (int32_t e = 0; e < c.num_edges(); ++e) {
        const int32_t f = c.face_of(c.halfedges(e)[0]);
        if (misoriented(m, c, e) && sheets.orientable[size_t(sheets.sheet[size_t(f)])])
          refuse("faces " + std::to_string(input_face(f)) + " and " +
                 std::to_string(input_face(c.face_of(c.halfedges(e)[1]))) +
                 " disagree in orientation across edge " + edge_name(c.edge_vertices[size_t(e)]));
      }
    // Flip the minority of each orientable sheet; a tie keeps the first face.
    std::vector<int32_t> against(size_t(sheets.size()), 0);
    for (int32_t f = 0; f < m.num_faces(); ++f) against[size_t(sheets.sheet[size_t(f)])] += sheets.flipped[size_t(f)];
    int32_t flipped = 0, first_flipped = -1;
    for (int32_t f = 0; f < m.num_faces(); ++f) {
      const int32_t s = sheets.sheet[size_t(f)];
      const uint8_t wrong = 2 * against[size_t(s)] > sheets.faces[size_t(s)] ? 0 : 1;
      if (!sheets.orientable[size_t(s)] || sheets.flipped[size_t(f)] != wrong) continue;
      reverse_face(m, f);
      if (flipped++ == 0) first_flipped = f;
    }
    const auto non_orientable = std::count(sheets.orientable.begin(), sheets.orientable.end(), 0);
    const auto first_non_orientable = std::find(sheets.orientable.begin(), sheets.orientable.end(), 0) - sheets.orientable.begin();
    reoriented = flipped > 0;
    if (flipped > 0)
      repairs.push_back("re-oriented " + plural(flipped, "face", "faces") +
                        " to agree with their neighbours (first: face " + std::to_string(input_face(first_flipped)) + ")");
    if (non_orientable == 1)
      result.notices.push_back("component " + std::to_string(first_non_orientable) +
                        " is not orientable (Möbius-like); faces left as they are");
    else if (non_orientable > 1)
      result.notices.push_back(std::to_string(non_orientable) + " components are not orientable (Möbius-like; first: component " +
                        std::to_string(first_non_orientable) + "); faces left as they are");
  }

  // 6. Unreferenced vertices.
  if (const auto unused = std::count(used.begin(), used.end(), 0); unused > 0) {
    const auto first = std::find(used.begin(), used.end(), 0) - used.begin();
    if (options.strict)
      refuse(unused == 1 ? "vertex " + std::to_string(first) + " is not used by any face"
                         : std::to_string(unused) + " vertices are not used by any face (first: " + std::to_string(first) + ")");
    const std::vector<int32_t> index = keep_vertices(m, used);
    // The renumbering keeps the vertex order, so edges keep their (lo, hi) order too.
    for (auto& ends : c.edge_vertices) ends = {index[size_t(ends[0])], index[size_t(ends[1])]};
    repairs.push_back("dropped " + plural(unused, "unreferenced vertex", "unreferenced vertices") + " (first: vertex " +
                      std::to_string(first) + ")");
  }
  // Reversed faces renumber their halfedges; otherwise the last connectivity built still
  // describes the result, and the pipeline need not build it again.
  if (!reoriented) result.connectivity = std::move(c);
  result.mesh = std::move(m);
  return result;
}

} // namespace

RepairResult repair(PolygonMesh&& mesh, std::string_view name, const RepairOptions& options) {
  const std::string prefix = std::string(name) + ": ";
  if (options.max_faces > 0 && mesh.num_faces() > options.max_faces)
    throw InputError(prefix + std::to_string(mesh.num_faces()) + " faces, more than the limit of " +
                     std::to_string(options.max_faces));
  const bool scattered = options.reorder && is_scattered(mesh);
  if (scattered && all_in_range(mesh.face_vertices, mesh.num_vertices())) {
    // The reordered mesh is tried first, strict, so that it stops at the first problem and
    // leaves the mesh as it was: a mesh that needs anything is repaired in its own order,
    // brought back from the reordered one, so that every message names the input's
    // elements. The input is not kept beside it (209 MiB of the run's peak on 10M
    // shuffled triangles).
    const MeshOrder order = locality_order(mesh);
    PolygonMesh local = reordered(mesh, order);
    mesh = PolygonMesh();
    RepairOptions first_problem = options;
    first_problem.strict = true;
    try {
      RepairResult result = repair_in_order(local, prefix, first_problem);
      if (result.notices.empty()) {
        result.reordered = true;
        return result;
      }
      local = std::move(result.mesh);
    } catch (const Error&) {
    }
    mesh = restored(local, order);
  }
  RepairResult result = repair_in_order(mesh, prefix, options);
  if (scattered) { // its messages are told: the rest can run in order
    result.mesh = reordered(result.mesh, locality_order(result.mesh));
    result.connectivity = Connectivity();
    result.reordered = true;
  }
  return result;
}

} // namespace meander
