#include "meander/check.h"

#include "meander/connectivity.h"
#include "meander/error.h"
#include "meander/locality.h"
#include "chunks.h"
#include "mesh_scan.h"
#include "union_find.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <span>
#include <utility>

#include <tbb/enumerable_thread_specific.h>

namespace meander {

namespace {

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

RepairResult repair(const PolygonMesh& mesh, std::string_view name, const RepairOptions& options) {
  return repair(PolygonMesh(mesh), name, options);
}

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
