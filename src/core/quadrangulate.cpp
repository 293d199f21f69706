#include "meander/quadrangulate.h"

#include "meander/error.h"

#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meander {

namespace {

void require_manifold_edges(const Connectivity& c) {
  for (int32_t e = 0; e < c.num_edges(); ++e)
    if (c.edge_degree(e) > 2)
      throw TopologyError("edge (" + std::to_string(c.edge_vertices[size_t(e)][0]) + "," +
                          std::to_string(c.edge_vertices[size_t(e)][1]) + ") is shared by " +
                          std::to_string(c.edge_degree(e)) + " faces: mesh is not manifold");
}

// A triangle's face point is its incentre, any other face's its centroid. A needle's
// centroid lies almost on its long sides, so the dual-of-Simplest triangles on them are
// flat (an angle near 180 degrees at the face point) and the cycle turns back inside
// them, where a variable wire's slabs fold over each other. At the incentre the angle
// facing side e is 90 degrees plus half the face's angle opposite e: below 135 degrees
// unless the face is obtuse (caps: flip_caps.h).
Vec3 face_point(const PolygonMesh& mesh, std::span<const Vec3> positions, int32_t f) {
  if (mesh.face_size(f) != 3) return centroid(positions, mesh.face(f));
  const auto v = mesh.face(f);
  const Vec3 a = positions[size_t(v[0])], b = positions[size_t(v[1])], c = positions[size_t(v[2])];
  // Each corner weighted by the length of the side opposite it.
  const double wa = norm(c - b), wb = norm(a - c), wc = norm(b - a), sum = wa + wb + wc;
  if (!(sum > 0)) return a;
  const auto blend = [&](float Vec3::*axis) { return float((wa * a.*axis + wb * b.*axis + wc * c.*axis) / sum); };
  return {blend(&Vec3::x), blend(&Vec3::y), blend(&Vec3::z)};
}

// Side adjacency of a quad mesh given as polygons (every face a quad), from its edges.
QuadMesh quads_with_adjacency(PolygonMesh quad_faces) {
  const Connectivity c = build_connectivity(quad_faces);
  require_manifold_edges(c);
  QuadMesh q;
  q.positions = std::move(quad_faces.positions);
  const int32_t n = quad_faces.num_faces();
  q.quads.resize(size_t(n));
  q.neighbors.assign(size_t(n), {-1, -1, -1, -1});
  for (int32_t f = 0; f < n; ++f)
    for (int k = 0; k < 4; ++k) q.quads[size_t(f)][size_t(k)] = quad_faces.face_vertices[size_t(4 * f + k)];
  for (int32_t e = 0; e < c.num_edges(); ++e) {
    if (c.edge_degree(e) != 2) continue;
    const int32_t a = c.halfedges(e)[0], b = c.halfedges(e)[1];
    q.neighbors[size_t(a / 4)][size_t(a % 4)] = b;
    q.neighbors[size_t(b / 4)][size_t(b % 4)] = a;
  }
  return q;
}

// Dual of Simplest in three passes, each reading fewer of the input's arrays, so that the
// consuming overload can release them in between (`release(pass)` after each pass): the
// quads are the largest arrays so far, and every page the run takes fresh costs more than
// the work done in it on a virtual machine.
template <typename Release>
QuadMesh dual_simplest_passes(const PolygonMesh& mesh, std::vector<Vec3>&& positions, const Connectivity& c,
                              Release&& release) {
  const int32_t nv = int32_t(positions.size());
  const int32_t nf = mesh.num_faces();
  const int32_t ne = c.num_edges();
  QuadMesh q;
  q.face_point_offset = nv;

  // 1. Quad e has corners (x, F_b, y, F_a) where its first halfedge a runs x -> y in face
  // F_a and its second halfedge b lies in face F_b. Each halfedge h of face F touches two
  // black edges of its quad: (F, tail h) and (head h, F); sides[h] says which quad sides
  // those are (tail side in bits 0-1, head side in bits 2-3, `half` for the one halfedge
  // of a half quad). The second halfedge may run either way (non-orientable or
  // misoriented input), which changes its sides. Every loop writes only its own
  // elements, so each runs in parallel.
  q.quads.resize(size_t(ne)); // each written below
  std::vector<uint8_t> sides(size_t(mesh.num_corners()));
  constexpr auto pack = [](int tail, int head) { return uint8_t(tail | head << 2); };
  constexpr uint8_t half = 16; // the halfedge's quad is a half quad
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, ne, 1 << 14), [&](const tbb::blocked_range<int32_t>& edges) {
    for (int32_t e = edges.begin(); e < edges.end(); ++e) {
      const auto hs = c.halfedges(e);
      const int32_t a = hs[0];
      const int32_t x = mesh.face_vertices[size_t(a)];
      const int32_t y = halfedge_target(mesh, c, a);
      const int32_t fa = nv + c.face_of(a);
      if (hs.size() == 1) {
        sides[size_t(a)] = pack(3, 2) | half;
        q.quads[size_t(e)] = {x, -1, y, fa};
        continue;
      }
      sides[size_t(a)] = pack(3, 2);
      const int32_t b = hs[1];
      q.quads[size_t(e)] = {x, nv + c.face_of(b), y, fa};
      sides[size_t(b)] = mesh.face_vertices[size_t(b)] == x ? pack(0, 1) : pack(1, 0);
    }
  });
  release(1);

  // 2. Face points after the vertices.
  q.positions = std::move(positions);
  q.positions.resize(size_t(nv) + size_t(nf));
  const std::span<const Vec3> vertices(q.positions.data(), size_t(nv));
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, nf, 1 << 14), [&](const tbb::blocked_range<int32_t>& faces) {
    for (int32_t f = faces.begin(); f < faces.end(); ++f) q.positions[size_t(nv + f)] = face_point(mesh, vertices, f);
  });
  release(2);

  // 3. The black edge (F, v) at the corner where halfedge h enters v and next(h) leaves it
  // is shared by the quads of h and next(h); each quad side is written by one corner, and
  // the sides no corner writes (a half quad's 0 and 1) are written -1 by the half quad's
  // one halfedge. Faces of one size are found without face_start, which is released by then.
  q.neighbors.resize(size_t(ne)); // each side written below
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, nf, 1 << 14), [&](const tbb::blocked_range<int32_t>& faces) {
    for (int32_t f = faces.begin(); f < faces.end(); ++f) {
      const int32_t first = c.face_size > 0 ? f * c.face_size : mesh.face_start[f];
      const int32_t last = c.face_size > 0 ? first + c.face_size : mesh.face_start[f + 1];
      for (int32_t h = first; h < last; ++h) {
        const int32_t g = h + 1 == last ? first : h + 1;
        const int32_t qh = c.halfedge_edge[size_t(h)], qg = c.halfedge_edge[size_t(g)];
        const int head = (sides[size_t(h)] >> 2) & 3, tail = sides[size_t(g)] & 3;
        q.neighbors[size_t(qh)][size_t(head)] = 4 * qg + tail;
        q.neighbors[size_t(qg)][size_t(tail)] = 4 * qh + head;
        if (sides[size_t(h)] & half) q.neighbors[size_t(qh)][0] = q.neighbors[size_t(qh)][1] = -1;
      }
    }
  });
  return q;
}

} // namespace

QuadMesh dual_simplest(const PolygonMesh& mesh, const Connectivity& c) {
  require_manifold_edges(c);
  return dual_simplest_passes(mesh, std::vector<Vec3>(mesh.positions), c, [](int) {});
}

QuadMesh dual_simplest(PolygonMesh&& mesh, Connectivity&& c) {
  require_manifold_edges(c);
  decltype(c.edge_vertices)().swap(c.edge_vertices);
  QuadMesh q = dual_simplest_passes(mesh, std::move(mesh.positions), c, [&](int pass) {
    if (pass == 1) { // the quads' corners are known: only the corners' edges are left to read
      decltype(c.halfedge_face)().swap(c.halfedge_face);
      decltype(c.edge_halfedges)().swap(c.edge_halfedges);
      decltype(c.edge_start)().swap(c.edge_start);
    } else { // the face points are placed: faces are only walked round from here on
      std::vector<int32_t>().swap(mesh.face_vertices);
      if (c.face_size > 0) std::vector<int32_t>().swap(mesh.face_start);
    }
  });
  mesh = PolygonMesh();
  c = Connectivity();
  return q;
}

QuadMesh catmull_clark_quads(const PolygonMesh& mesh, const Connectivity& c) {
  require_manifold_edges(c);
  const int32_t nv = mesh.num_vertices();
  const int32_t ne = c.num_edges();
  const int32_t nf = mesh.num_faces();
  PolygonMesh out;
  out.positions.reserve(size_t(nv) + size_t(ne) + size_t(nf));
  out.positions.assign(mesh.positions.begin(), mesh.positions.end());
  for (int32_t e = 0; e < ne; ++e) {
    const auto [u, v] = c.edge_vertices[size_t(e)];
    out.positions.push_back((mesh.positions[size_t(u)] + mesh.positions[size_t(v)]) * 0.5f);
  }
  for (int32_t f = 0; f < nf; ++f) out.positions.push_back(centroid(mesh.positions, mesh.face(f)));
  out.face_vertices.reserve(size_t(mesh.num_corners()) * 4);
  out.face_start.reserve(size_t(mesh.num_corners()) + 1);
  for (int32_t f = 0; f < nf; ++f) {
    const int32_t first = mesh.face_start[f], last = mesh.face_start[f + 1];
    for (int32_t h = first; h < last; ++h) {
      const int32_t prev = h == first ? last - 1 : h - 1;
      out.add_face({mesh.face_vertices[size_t(h)], nv + c.halfedge_edge[size_t(h)], nv + ne + f,
                    nv + c.halfedge_edge[size_t(prev)]});
    }
  }
  return quads_with_adjacency(std::move(out));
}

QuadMesh quads_as_is(const PolygonMesh& mesh, const Connectivity& c) {
  require_manifold_edges(c);
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    if (mesh.face_size(f) != 4)
      throw TopologyError("face " + std::to_string(f) + " has " + std::to_string(mesh.face_size(f)) +
                          " vertices: quad none needs a mesh of quads only (use quad dual-simplest or "
                          "catmull-clark)");
  return quads_with_adjacency(mesh);
}

int32_t count_open_sides(const QuadMesh& q) {
  int32_t open = 0;
  for (int32_t i = 0; i < q.num_quads(); ++i)
    for (int k = q.is_half(i) ? 2 : 0; k < 4; ++k) open += q.neighbors[size_t(i)][size_t(k)] < 0;
  return open;
}

Quadrangulation parse_quadrangulation(std::string_view name) {
  if (name == "dual-simplest") return Quadrangulation::dual_simplest;
  if (name == "catmull-clark") return Quadrangulation::catmull_clark;
  if (name == "none") return Quadrangulation::none;
  throw UsageError("unknown quadrangulation '" + std::string(name) + "' (expected dual-simplest, catmull-clark or none)");
}

} // namespace meander
