// The passes over a polygon mesh's faces and edges that inspection (inspect.cpp) and
// repair (repair.cpp) share: degenerate faces, the edge scan (boundary, non-manifold,
// misoriented, duplicate faces, fans) and the sheets of consistently wound faces.
// Internal to the library.
#pragma once

#include "meander/connectivity.h"
#include "meander/mesh.h"
#include "union_find.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace meander {

// "1 face", "2 faces".
std::string plural(int64_t n, std::string_view one, std::string_view many);

inline bool in_range(int32_t v, int32_t num_vertices) { return uint32_t(v) < uint32_t(num_vertices); }

inline bool all_in_range(std::span<const int32_t> face, int32_t num_vertices) {
  return std::all_of(face.begin(), face.end(), [&](int32_t v) { return in_range(v, num_vertices); });
}

// Finds a vertex that occurs twice in a face, in time linear in the face size whatever
// the size. The faces must index in range.
class RepeatFinder {
public:
  explicit RepeatFinder(int32_t num_vertices) : num_vertices_(num_vertices) {}

  // The vertex whose second occurrence comes first, or -1.
  int32_t operator()(std::span<const int32_t> face) {
    if (face.size() <= kPairwiseSearch) {
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
  // Faces up to this size are searched pairwise: cheaper than a per-vertex stamp array
  // for the triangles and quads that make up nearly every mesh.
  static constexpr size_t kPairwiseSearch = 8;

  int32_t num_vertices_;
  int32_t round_ = -1;
  std::vector<int32_t> stamp_;
};

// Why face `input_face` (of `size` vertices as given, `repeated` what RepeatFinder said)
// is not a polygon.
std::string degenerate_reason(int32_t input_face, size_t size, int32_t repeated);

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
inline int32_t keep_face(std::span<const int32_t> face, int32_t* out) {
  if (out != face.data()) std::copy(face.begin(), face.end(), out); // out lies before face: a forward copy is safe
  return int32_t(face.size());
}

struct FaceCleanup {
  int32_t collapsed = 0; // kept once repeated consecutive vertices were collapsed
  int32_t dropped = 0;   // fewer than 3 vertices, or a vertex repeated, after collapsing
  std::string first_collapsed, first_dropped;
};

// Repair step 2 (check.h): collapses repeated consecutive vertices and drops the faces
// left with fewer than 3 or still repeating one. Faces with an index out of range are
// dropped silently: repair refused them before, and inspect counts them apart but keeps
// them out of the topology.
FaceCleanup clean_faces(PolygonMesh& m, std::vector<int32_t>& origin);

// A manifold edge whose two faces both run from the same vertex to the other.
bool misoriented(const PolygonMesh& m, const Connectivity& c, int32_t e);

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

EdgeScan scan_edges(const PolygonMesh& m, const Connectivity& c);

// Number of fans at each vertex.
std::vector<int32_t> count_fans(const PolygonMesh& m, const UnionFind& fans);

// Faces joined across manifold edges ("sheets"), each face with its winding relative to
// its sheet's first face.
struct Sheets {
  std::vector<int32_t> sheet;      // per face; sheets are numbered by their first face
  std::vector<uint8_t> flipped;    // per face: wound against its sheet's first face
  std::vector<int32_t> faces;      // per sheet
  std::vector<uint8_t> orientable; // per sheet
  int32_t size() const { return int32_t(faces.size()); }
};

Sheets find_sheets(const PolygonMesh& m, const Connectivity& c);

} // namespace meander
