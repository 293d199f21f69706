#include "sculpture/sampled_shell.h"

#include "meander/closest_points.h"
#include "meander/error.h"
#include "meander/printability.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_domain_with_polyline_features_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Mesh_3/Protect_edges_sizing_field.h>
#include <CGAL/refine_mesh_3.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <unordered_map>

namespace meander {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Domain = CGAL::Mesh_domain_with_polyline_features_3<CGAL::Labeled_mesh_domain_3<K>>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using Triangle = std::array<int32_t, 3>;

Vec3d unit(Vec3d v) {
  const double length = norm(v);
  return length > 0 ? v * (1 / length) : Vec3d{};
}

// The surface's normals for the sign of a point's distance (Bærentzen and Aanæs'
// angle-weighted pseudo-normals: on the inside wherever its nearest point is, at a face,
// an edge or a corner, if the surface is a closed 2-manifold), and per triangle side the
// triangle on its other side (-1 on the surface's boundary).
struct Normals {
  std::vector<Vec3d> face, vertex;
  std::vector<int32_t> across; // 3 per triangle: side k goes from corner k to k + 1
};

Normals normals_of(const PaintedSurface& s) {
  Normals n;
  n.face.resize(s.triangles.size());
  n.vertex.assign(s.positions.size(), Vec3d{});
  std::vector<std::tuple<int32_t, int32_t, int32_t>> sides;
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    const Triangle& c = s.triangles[t];
    Vec3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = to_double(s.positions[size_t(c[size_t(k)])]);
    n.face[t] = unit(cross(p[1] - p[0], p[2] - p[0]));
    for (int k = 0; k < 3; ++k) {
      const Vec3d e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
      n.vertex[size_t(c[size_t(k)])] = n.vertex[size_t(c[size_t(k)])] + n.face[t] * std::atan2(norm(cross(e1, e2)), dot(e1, e2));
      const int32_t a = c[size_t(k)], b = c[size_t((k + 1) % 3)];
      sides.emplace_back(std::min(a, b), std::max(a, b), int32_t(3 * t) + k);
    }
  }
  for (Vec3d& v : n.vertex) v = unit(v);
  std::sort(sides.begin(), sides.end());
  n.across.assign(sides.size(), -1);
  for (size_t i = 0; i + 1 < sides.size(); ++i)
    if (std::get<0>(sides[i]) == std::get<0>(sides[i + 1]) && std::get<1>(sides[i]) == std::get<1>(sides[i + 1])) {
      n.across[size_t(std::get<2>(sides[i]))] = std::get<2>(sides[i + 1]) / 3;
      n.across[size_t(std::get<2>(sides[i + 1]))] = std::get<2>(sides[i]) / 3;
    }
  return n;
}

// The pseudo-normal where `hit` lies on its triangle: the face's inside it, the sum of
// the two faces' on a side, the corner's at a corner.
Vec3d pseudo_normal(const PaintedSurface& s, const Normals& n, const ClosestPoints::Hit& hit) {
  const size_t t = size_t(hit.triangle);
  const Triangle& c = s.triangles[t];
  const Vec3d a = to_double(s.positions[size_t(c[0])]), b = to_double(s.positions[size_t(c[1])]),
              d = to_double(s.positions[size_t(c[2])]);
  // Barycentric coordinates of the hit, each the area opposite a corner.
  const Vec3d normal = cross(b - a, d - a);
  const double area = dot(normal, normal);
  if (area == 0) return n.face[t];
  const double w[3] = {dot(cross(d - b, hit.point - b), normal) / area, dot(cross(a - d, hit.point - d), normal) / area,
                       dot(cross(b - a, hit.point - a), normal) / area};
  constexpr double on = 1e-7;
  int zeros = 0, corner = -1, side = -1;
  for (int k = 0; k < 3; ++k)
    if (w[k] < on) {
      ++zeros;
      side = (k + 1) % 3; // the side opposite corner k
    } else {
      corner = k;
    }
  if (zeros == 0) return n.face[t];
  if (zeros == 1) {
    const int32_t other = n.across[3 * t + size_t(side)];
    return other < 0 ? n.face[t] : n.face[t] + n.face[size_t(other)];
  }
  return n.vertex[size_t(c[size_t(corner)])];
}

// The surface's boundary and (with `cut`) the regions' common one, as polylines between
// the points where more or fewer than two such edges meet (closed where none do): the
// curves the mesher keeps as edges, so that the colours part along the painted line.
std::vector<std::vector<Point>> features_of(const PaintedSurface& s, const Normals& n, bool cut) {
  std::vector<std::pair<int32_t, int32_t>> edges; // both ways round
  for (size_t t = 0; t < s.triangles.size(); ++t)
    for (size_t k = 0; k < 3; ++k) {
      const int32_t other = n.across[3 * t + k];
      const bool boundary = other < 0 || (cut && other > int32_t(t) && s.region[size_t(other)] != s.region[t]);
      if (!boundary) continue;
      const int32_t a = s.triangles[t][k], b = s.triangles[t][(k + 1) % 3];
      edges.emplace_back(a, b);
      edges.emplace_back(b, a);
    }
  std::sort(edges.begin(), edges.end());
  std::unordered_map<int32_t, int32_t> degree;
  for (const auto& e : edges) ++degree[e.first];
  std::vector<uint8_t> used(edges.size(), 0);
  const auto edge_index = [&](int32_t a, int32_t b) {
    return size_t(std::lower_bound(edges.begin(), edges.end(), std::make_pair(a, b)) - edges.begin());
  };
  const auto point = [&](int32_t v) {
    const Vec3 p = s.positions[size_t(v)];
    return Point(p.x, p.y, p.z);
  };
  std::vector<std::vector<Point>> lines;
  // From each end (a point of degree other than 2), then round each closed loop left.
  for (int pass = 0; pass < 2; ++pass)
    for (size_t i = 0; i < edges.size(); ++i) {
      if (used[i] || (pass == 0 && degree[edges[i].first] == 2)) continue;
      std::vector<Point> line{point(edges[i].first)};
      size_t e = i;
      for (;;) {
        used[e] = 1;
        used[edge_index(edges[e].second, edges[e].first)] = 1;
        const int32_t v = edges[e].second;
        line.push_back(point(v));
        if (degree[v] != 2) break;
        const size_t first = edge_index(v, INT32_MIN);
        e = used[first] ? first + 1 : first;
        if (used[e]) break; // round the loop
      }
      // In pieces of a few dozen points: CGAL finds a point on a polyline by walking it.
      constexpr size_t piece = 32;
      for (size_t start = 0; start + 1 < line.size(); start += piece)
        lines.emplace_back(line.begin() + ptrdiff_t(start), line.begin() + ptrdiff_t(std::min(line.size(), start + piece + 1)));
    }
  return lines;
}

// Which region's solid a point is in (1 or 2), or 0: outside the surface, deeper than
// the wall, or (with a clearance) near where the two solids would meet.
class Labels {
public:
  Labels(const PaintedSurface& s, const Normals& n, double wall, double clearance)
      : s_(s), n_(n), wall_(wall), reach_(0.3 * clearance), closest_(surface_of(s, 2)),
        regions_{ClosestPoints(clearance > 0 ? surface_of(s, 0) : PolygonMesh{}),
                 ClosestPoints(clearance > 0 ? surface_of(s, 1) : PolygonMesh{})} {}

  int operator()(const Point& x) const {
    const Vec3d p{x.x(), x.y(), x.z()};
    const ClosestPoints::Hit hit = closest_.closest_hit(p, last_, wall_);
    if (hit.triangle < 0) return 0;
    last_ = hit;
    const Vec3d out = p - last_.point;
    if (dot(out, out) >= wall_ * wall_ || dot(out, pseudo_normal(s_, n_, last_)) >= 0) return 0;
    const int region = s_.region[size_t(last_.triangle)];
    return reach_ > 0 && near_other(p, hit, region, reach_) ? 0 : 1 + region;
  }

  // How deep x lies under the surface if within about `reach` of where the regions'
  // solids would meet (to mesh finer there), else -1.
  double near_cut(const Point& x, double reach) const {
    const Vec3d p{x.x(), x.y(), x.z()};
    if (p == near_.first) return near_.second; // the sizes of a facet asked in turn
    const ClosestPoints::Hit hit = closest_.closest_hit(p, last_, wall_ + reach);
    if (hit.triangle >= 0) last_ = hit;
    near_ = {p, hit.triangle >= 0 && near_other(p, hit, s_.region[size_t(hit.triangle)], reach) ? norm(p - hit.point) : -1.0};
    return near_.second;
  }

private:
  static PolygonMesh surface_of(const PaintedSurface& s, int region) { // 2: both
    PolygonMesh m;
    m.positions.assign(s.positions.begin(), s.positions.end());
    for (size_t t = 0; t < s.triangles.size(); ++t)
      if (region == 2 || s.region[t] == region) m.add_face(s.triangles[t]);
    return m;
  }

  // Whether a point within `reach` of p could be nearer the other region than p's
  // nearest point of the surface, `hit` (in `region`): whether p lies within `reach` of
  // the plane halfway between that point and some point of the other region (tried at
  // each triangle's point nearest p and its corners). The points left out of both solids
  // so are those within `reach` of where they would meet (more at the surface, where that
  // plane lies halfway to the cut: twice `reach` from the cut), so the solids lie twice
  // `reach` apart.
  bool near_other(Vec3d p, const ClosestPoints::Hit& hit, int region, double reach) const {
    const Vec3d a = hit.point;
    const double d = norm(p - a);
    const auto near = [&](Vec3d y) { return dot(p - y, p - y) - d * d < 2 * reach * norm(y - a); };
    // |p - y|² - d² < 2 reach |a - y| <= 2 reach (d + |p - y|): y lies within d + 2 reach.
    return regions_[1 - size_t(region)].any_near(p, d + 2 * reach, [&](Vec3d closest, const std::array<Vec3d, 3>& corners) {
      return near(closest) || near(corners[0]) || near(corners[1]) || near(corners[2]);
    });
  }

  const PaintedSurface& s_;
  const Normals& n_;
  // With a clearance, 0.3 of it (near_other): the solids lie 0.6 of it apart, a margin
  // for the sampled walls (within a tenth of it of where they should be), above 0.45.
  double wall_, reach_;
  ClosestPoints closest_;
  std::array<ClosestPoints, 2> regions_; // each region's triangles, with a clearance
  // The mesher asks about points near each other in turn.
  mutable ClosestPoints::Hit last_;
  mutable std::pair<Vec3d, double> near_{Vec3d{NAN, NAN, NAN}, -1};
};

// Points on both sides of the wall, a few to a wall's width: the mesher only finds a
// surface where it looks across it, and would miss most of a wall thinner than the
// spaces between its first points. Each surface point (a corner of the triangles, and
// points on a lattice over larger ones) shoots a short segment in through the outside
// and one on through the inside, and where they cross a label's boundary a point is
// put in, unless it lies in a ball that protects a kept edge.
void seed(C3t3& c3t3, const Domain& domain, const PaintedSurface& s, const Normals& n, double wall, double spacing) {
  Tr& tr = c3t3.triangulation();
  const auto intersection = domain.construct_intersection_object();
  const auto weighted = tr.geom_traits().construct_weighted_point_3_object();
  const auto compare_weight = tr.geom_traits().compare_weighted_squared_radius_3_object();
  std::vector<std::pair<Vec3d, Vec3d>> starts; // a surface point and its normal
  for (size_t v = 0; v < s.positions.size(); ++v) starts.emplace_back(to_double(s.positions[v]), n.vertex[v]);
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    const Vec3d a = to_double(s.positions[size_t(s.triangles[t][0])]), b = to_double(s.positions[size_t(s.triangles[t][1])]),
                c = to_double(s.positions[size_t(s.triangles[t][2])]);
    const int steps = int(std::ceil(std::max({norm(b - a), norm(c - b), norm(a - c)}) / spacing));
    for (int i = 1; i < steps; ++i)
      for (int j = 1; i + j < steps; ++j)
        starts.emplace_back(a + (b - a) * (double(i) / steps) + (c - a) * (double(j) / steps), n.face[t]);
  }
  // One start per cell of the spacing, the first there.
  std::unordered_map<uint64_t, uint8_t> taken;
  const auto key = [&](Vec3d p) {
    const auto cell = [&](double x) { return uint64_t(int64_t(std::floor(x / spacing)) & 0x1fffff); };
    return cell(p.x) << 42 | cell(p.y) << 21 | cell(p.z);
  };
  for (const auto& [p, normal] : starts) {
    if (norm(normal) == 0 || !taken.emplace(key(p), 1).second) continue;
    const auto at = [&](double depth) {
      const Vec3d q = p - normal * depth;
      return Point(q.x, q.y, q.z);
    };
    for (const K::Segment_3 segment : {K::Segment_3(at(-0.25 * wall), at(0.5 * wall)), K::Segment_3(at(0.5 * wall), at(1.5 * wall))}) {
      const Domain::Intersection crossing = intersection(segment);
      if (std::get<2>(crossing) == 0) continue;
      const Tr::Weighted_point point = weighted(std::get<0>(crossing));
      if (tr.dimension() == 3) {
        Tr::Locate_type type;
        int li, lj;
        const Tr::Cell_handle cell = tr.locate(point, type, li, lj);
        if (tr.side_of_power_sphere(cell, point, true) != CGAL::ON_BOUNDED_SIDE) continue;
        std::vector<Tr::Vertex_handle> near;
        tr.vertices_on_conflict_zone_boundary(point, cell, std::back_inserter(near));
        const bool protected_ball = std::any_of(near.begin(), near.end(), [&](Tr::Vertex_handle v) {
          if (tr.is_infinite(v) || compare_weight(tr.point(v), 0) == CGAL::EQUAL) return false;
          return compare_weight(tr.point(v), -tr.min_squared_distance(std::get<0>(crossing), tr.point(v).point())) !=
                 CGAL::LARGER;
        });
        if (protected_ball) continue;
      }
      const Tr::Vertex_handle v = tr.insert(point);
      if (v == Tr::Vertex_handle()) continue;
      c3t3.set_dimension(v, 2);
      c3t3.set_index(v, std::get<1>(crossing));
    }
  }
}

int label_of(const C3t3& c3t3, Tr::Cell_handle c) { return c3t3.is_in_complex(c) ? c3t3.subdomain_index(c) : 0; }

// The labels of the cells round each corner of `cell`, as bits (bit k for label k).
unsigned labels_round(const C3t3& c3t3, Tr::Cell_handle cell) {
  unsigned labels = 0;
  std::vector<Tr::Cell_handle> star;
  for (int i = 0; i < 4; ++i) {
    star.clear();
    c3t3.triangulation().incident_cells(cell->vertex(i), std::back_inserter(star));
    for (const Tr::Cell_handle c : star) labels |= 1u << label_of(c3t3, c);
  }
  return labels;
}

// Relabels a cell; with pieces kept `apart`, never to touch the other solid, even at a
// corner. Returns whether it did.
bool set_label(C3t3& c3t3, Tr::Cell_handle cell, int label, bool apart) {
  if (c3t3.triangulation().is_infinite(cell) || label_of(c3t3, cell) == label) return false;
  if (apart && label != 0 && (labels_round(c3t3, cell) >> (3 - label) & 1)) return false;
  if (c3t3.is_in_complex(cell)) c3t3.remove_from_complex(cell);
  if (label != 0) c3t3.add_to_complex(cell, label);
  return true;
}

// With pieces kept apart: where the two solids' cells still meet, at a facet, an edge or
// a corner (the gap between them narrower than the cells there), the cells round the
// corner of the solid with fewer there leave it. Returns whether it relabelled any.
bool separate(C3t3& c3t3) {
  const Tr& tr = c3t3.triangulation();
  std::vector<std::pair<Tr::Cell_handle, int>> relabel;
  std::vector<Tr::Cell_handle> star;
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
    star.clear();
    tr.incident_cells(v, std::back_inserter(star));
    std::array<int, 3> count{};
    for (const Tr::Cell_handle c : star) ++count[size_t(label_of(c3t3, c))];
    if (count[1] == 0 || count[2] == 0) continue;
    const int fewer = count[1] < count[2] ? 1 : 2;
    for (const Tr::Cell_handle c : star)
      if (label_of(c3t3, c) == fewer) relabel.emplace_back(c, 0);
  }
  bool changed = false;
  for (const auto& [cell, label] : relabel) changed |= set_label(c3t3, cell, label, true);
  return changed;
}

// The label most of these cells have (the higher of a tie).
int most_common(const C3t3& c3t3, std::span<const Tr::Cell_handle> cells) {
  std::array<int, 3> count{};
  for (const Tr::Cell_handle c : cells) ++count[size_t(label_of(c3t3, c))];
  int most = 0;
  for (int k = 1; k < 3; ++k)
    if (count[size_t(k)] >= count[size_t(most)]) most = k;
  return most;
}

// Whether the cells of `cells` (all round one edge) with a label in `labels` (bit k for
// label k) form more than one group joined across facets.
bool split(const C3t3& c3t3, std::span<const Tr::Cell_handle> cells, unsigned labels) {
  std::vector<Tr::Cell_handle> group;
  for (const Tr::Cell_handle c : cells)
    if (labels >> label_of(c3t3, c) & 1) group.push_back(c);
  if (group.size() < 2) return false;
  std::vector<uint8_t> reached(group.size(), 0);
  std::vector<size_t> stack{0};
  reached[0] = 1;
  while (!stack.empty()) {
    const Tr::Cell_handle c = group[stack.back()];
    stack.pop_back();
    for (size_t j = 0; j < group.size(); ++j)
      if (!reached[j] && c->has_neighbor(group[j])) reached[j] = 1, stack.push_back(j);
  }
  return std::find(reached.begin(), reached.end(), 0) != reached.end();
}

// Where a solid's cells, or (unless the pieces are kept apart) the shell's, meet only
// along an edge (a neck of a region narrower than the cells), the cells round the edge
// take the label most of them have, until none is left. Returns whether it relabelled
// any; throws TopologyError when that does not end within a few rounds.
bool unpinch(C3t3& c3t3, bool apart) {
  const Tr& tr = c3t3.triangulation();
  std::unordered_map<const void*, size_t> order; // of the vertices, not of their addresses
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) order.emplace(&*v, order.size());
  bool changed = false;
  for (int round = 0; round < 20; ++round) {
    std::vector<std::pair<Tr::Cell_handle, int>> relabel;
    // Each edge once, from its first corner: the cells round it.
    for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
      std::vector<Tr::Vertex_handle> others;
      tr.finite_adjacent_vertices(v, std::back_inserter(others));
      for (const Tr::Vertex_handle w : others) {
        if (order.at(&*w) < order.at(&*v)) continue;
        Tr::Cell_handle c;
        int i, j;
        if (!tr.is_edge(v, w, c, i, j)) continue;
        std::vector<Tr::Cell_handle> ring;
        auto around = tr.incident_cells(Tr::Edge(c, i, j)), first = around;
        do ring.push_back(around); while (++around != first);
        if (!split(c3t3, ring, 0b010) && !split(c3t3, ring, 0b100) && (apart || !split(c3t3, ring, 0b110))) continue;
        const int label = most_common(c3t3, ring);
        for (const Tr::Cell_handle r : ring) relabel.emplace_back(r, label);
      }
    }
    bool relabelled = false;
    for (const auto& [cell, label] : relabel) relabelled |= set_label(c3t3, cell, label, apart);
    if (!relabelled) return changed;
    changed = true;
  }
  throw TopologyError("shell: the sampled solids still touch themselves along edges (a thinner --shell may not)");
}

// Where the cells outside the shell (or under it) round a corner are in more than one
// group (the shell's surface meets itself there at a point: a crease or a cavity's tip
// narrower than a cell), all but the largest group take the label most solid cells
// round the corner have. Returns whether it relabelled any.
bool fill_outside_tips(C3t3& c3t3, bool apart) {
  const Tr& tr = c3t3.triangulation();
  std::vector<std::pair<Tr::Cell_handle, int>> relabel;
  std::vector<Tr::Cell_handle> star, outside;
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
    star.clear();
    tr.incident_cells(v, std::back_inserter(star));
    outside.clear();
    std::array<int, 3> count{};
    for (const Tr::Cell_handle c : star) {
      ++count[size_t(label_of(c3t3, c))];
      if (label_of(c3t3, c) == 0) outside.push_back(c);
    }
    if (outside.size() < 2 || outside.size() == star.size()) continue;
    // The groups of outside cells joined across facets.
    std::vector<int> group(outside.size(), -1);
    std::vector<size_t> sizes;
    for (size_t i = 0; i < outside.size(); ++i) {
      if (group[i] >= 0) continue;
      group[i] = int(sizes.size());
      std::vector<size_t> stack{i};
      size_t size = 0;
      while (!stack.empty()) {
        const Tr::Cell_handle c = outside[stack.back()];
        stack.pop_back();
        ++size;
        for (size_t j = 0; j < outside.size(); ++j)
          if (group[j] < 0 && c->has_neighbor(outside[j])) group[j] = group[i], stack.push_back(j);
      }
      sizes.push_back(size);
    }
    if (sizes.size() < 2) continue;
    const int largest = int(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
    const int label = count[1] >= count[2] ? 1 : 2;
    for (size_t i = 0; i < outside.size(); ++i)
      if (group[i] != largest) relabel.emplace_back(outside[i], label);
  }
  bool changed = false;
  for (const auto& [cell, label] : relabel) changed |= set_label(c3t3, cell, label, apart);
  return changed;
}

// How many pieces of at least `area` each colour region of the surface is in (triangles
// joined across sides).
std::array<size_t, 2> pieces_of(const PaintedSurface& s, const Normals& n, double area) {
  std::array<size_t, 2> pieces{};
  std::vector<uint8_t> reached(s.triangles.size(), 0);
  std::vector<size_t> stack;
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    if (reached[t]) continue;
    double piece = 0;
    reached[t] = 1;
    stack.assign(1, t);
    while (!stack.empty()) {
      const size_t u = stack.back();
      stack.pop_back();
      const Vec3d a = to_double(s.positions[size_t(s.triangles[u][0])]);
      piece += norm(cross(to_double(s.positions[size_t(s.triangles[u][1])]) - a, to_double(s.positions[size_t(s.triangles[u][2])]) - a)) / 2;
      for (size_t k = 0; k < 3; ++k)
        if (const int32_t o = n.across[3 * u + k]; o >= 0 && !reached[size_t(o)] && s.region[size_t(o)] == s.region[u])
          reached[size_t(o)] = 1, stack.push_back(size_t(o));
    }
    if (piece >= area) ++pieces[size_t(s.region[t])];
  }
  return pieces;
}

// Groups of cells of one label (joined across facets) of a few dozen cells (a solid's tip
// or a neck narrower than the cells cut off, a pocket left inside a solid), and a
// solid's groups beyond the largest as many as its colour region has pieces a cell or
// more wide on the surface (`solid_pieces`) if small, take their neighbours' label.
// Returns whether it relabelled any.
bool drop_crumbs(C3t3& c3t3, std::array<size_t, 2> solid_pieces, bool apart) {
  const Tr& tr = c3t3.triangulation();
  std::unordered_map<const void*, uint8_t> reached;
  std::array<std::vector<std::vector<Tr::Cell_handle>>, 3> groups; // by label
  std::array<size_t, 3> cells{};
  for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) {
    const int k = label_of(c3t3, c);
    if (!reached.emplace(&*c, 1).second) continue;
    std::vector<Tr::Cell_handle> members{c};
    for (size_t m = 0; m < members.size(); ++m)
      for (int i = 0; i < 4; ++i)
        if (const Tr::Cell_handle n = members[m]->neighbor(i); label_of(c3t3, n) == k && reached.emplace(&*n, 1).second)
          members.push_back(n);
    cells[size_t(k)] += members.size();
    groups[size_t(k)].push_back(std::move(members));
  }
  // Outside the solids, any group of more than a few dozen cells stays.
  const std::array<size_t, 3> pieces{SIZE_MAX, solid_pieces[0], solid_pieces[1]};
  std::vector<std::pair<Tr::Cell_handle, int>> relabel;
  for (size_t k = 0; k < 3; ++k) {
    std::stable_sort(groups[k].begin(), groups[k].end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
    for (size_t g = 0; g < groups[k].size(); ++g) {
      const size_t size = groups[k][g].size();
      if (size > 64 && (g < pieces[k] || size > cells[k] / 20)) continue;
      std::vector<Tr::Cell_handle> around;
      for (const Tr::Cell_handle m : groups[k][g])
        for (int i = 0; i < 4; ++i)
          if (label_of(c3t3, m->neighbor(i)) != int(k)) around.push_back(m->neighbor(i));
      const int label = most_common(c3t3, around);
      for (const Tr::Cell_handle m : groups[k][g]) relabel.emplace_back(m, label);
    }
  }
  bool changed = false;
  for (const auto& [cell, label] : relabel) changed |= set_label(c3t3, cell, label, apart);
  return changed;
}

double volume_of(const PolygonMesh& m) {
  double volume = 0;
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    const std::span<const int32_t> t = m.face(f);
    volume += dot(to_double(m.positions[size_t(t[0])]), cross(to_double(m.positions[size_t(t[1])]), to_double(m.positions[size_t(t[2])]))) / 6;
  }
  return volume;
}

// The boundary of a set of cells, turned outward, and the triangulation's vertex each of
// its vertices is.
struct Boundary {
  PolygonMesh mesh;
  std::vector<Tr::Vertex_handle> origin;
};

// The boundary of the cells with a label in `labels` (bit k for label k).
Boundary boundary_of(const C3t3& c3t3, unsigned labels) {
  const auto in = [&](Tr::Cell_handle c) { return bool(labels >> label_of(c3t3, c) & 1); };
  const Tr& tr = c3t3.triangulation();
  std::unordered_map<const void*, int32_t> id;
  Boundary b;
  const auto vertex = [&](Tr::Vertex_handle v) {
    const auto [it, fresh] = id.emplace(&*v, int32_t(b.origin.size()));
    if (fresh) {
      const Point& p = tr.point(v).point();
      b.mesh.positions.push_back({float(p.x()), float(p.y()), float(p.z())});
      b.origin.push_back(v);
    }
    return it->second;
  };
  for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) {
    if (!in(c)) continue;
    for (int i = 0; i < 4; ++i) {
      if (in(c->neighbor(i))) continue;
      // Round cell c, the corners of its facet i in this order face out of it or all in.
      b.mesh.add_face({vertex(c->vertex(Tr::vertex_triple_index(i, 0))), vertex(c->vertex(Tr::vertex_triple_index(i, 1))),
                       vertex(c->vertex(Tr::vertex_triple_index(i, 2)))});
    }
  }
  if (volume_of(b.mesh) < 0) // all in
    for (int32_t f = 0; f < b.mesh.num_faces(); ++f)
      std::swap(b.mesh.face_vertices[size_t(3 * f + 1)], b.mesh.face_vertices[size_t(3 * f + 2)]);
  return b;
}

// Whether each side of each face is the side of exactly one other face, the other way
// round: a closed, oriented surface that touches itself along no edge.
bool closed(const PolygonMesh& m) {
  std::vector<std::pair<int32_t, int32_t>> sides;
  for (int32_t f = 0; f < m.num_faces(); ++f) {
    const std::span<const int32_t> t = m.face(f);
    for (size_t k = 0; k < 3; ++k) sides.emplace_back(t[k], t[(k + 1) % 3]);
  }
  std::sort(sides.begin(), sides.end());
  if (std::adjacent_find(sides.begin(), sides.end()) != sides.end()) return false;
  return std::all_of(sides.begin(), sides.end(), [&](const auto& e) {
    return std::binary_search(sides.begin(), sides.end(), std::make_pair(e.second, e.first));
  });
}

// The fans of faces round each vertex of a closed triangle mesh: for each corner
// (3 f + k), the first corner of its fan (the corners round a vertex joined across the
// faces' shared sides).
std::vector<int32_t> fans_of(const PolygonMesh& m) {
  std::unordered_map<uint64_t, int32_t> side_face; // directed side (a, b) -> its face
  const auto side = [](int32_t a, int32_t b) { return uint64_t(uint32_t(a)) << 32 | uint32_t(b); };
  for (int32_t f = 0; f < m.num_faces(); ++f)
    for (size_t k = 0; k < 3; ++k) side_face.emplace(side(m.face(f)[k], m.face(f)[(k + 1) % 3]), f);
  std::vector<int32_t> fan(size_t(3 * m.num_faces()));
  for (size_t c = 0; c < fan.size(); ++c) fan[c] = int32_t(c);
  const auto root = [&](int32_t c) {
    while (fan[size_t(c)] != c) c = fan[size_t(c)] = fan[size_t(fan[size_t(c)])];
    return c;
  };
  for (int32_t f = 0; f < m.num_faces(); ++f)
    for (int32_t k = 0; k < 3; ++k) {
      const std::span<const int32_t> t = m.face(f);
      const int32_t v = t[size_t(k)], g = side_face.at(side(t[size_t((k + 1) % 3)], v));
      const std::span<const int32_t> u = m.face(g);
      const int32_t a = root(3 * f + k), b = root(3 * g + int32_t(std::find(u.begin(), u.end(), v) - u.begin()));
      fan[size_t(std::max(a, b))] = std::min(a, b);
    }
  for (size_t c = 0; c < fan.size(); ++c) fan[c] = root(int32_t(c));
  return fan;
}

// Where a solid's surface, or the two solids' union, meets itself at a corner only (cones
// of cells tip to tip, at a neck narrower than a cell), each cone gets a corner of its
// own, moved a twentieth of the way to the middle of its far corners (into the cone), so
// that the cones part by far less than a print resolves. Both solids' fans of faces round
// a corner that share a face (along the cut) move together, so that the solids still
// meet there. Where that would keep a solid's own cones together (the other solid joins
// them), nothing moves: returns those corners and the solid's label. Each boundary must
// be closed; `ids` numbers the triangulation's vertices (in an order that does not depend
// on where they lie in memory).
std::vector<std::pair<Tr::Vertex_handle, int>> part_pinched_corners(std::array<Boundary, 2>& solids,
                                                                    const std::unordered_map<const void*, int32_t>& ids) {
  std::vector<std::pair<Tr::Vertex_handle, int>> unparted;
  std::array<std::vector<int32_t>, 2> fans{fans_of(solids[0].mesh), fans_of(solids[1].mesh)};
  // Classes of fans (a fan of solid k is node k * offset + its first corner), joined
  // where the solids share a face.
  const size_t offset = fans[0].size();
  std::vector<int32_t> parent(offset + fans[1].size());
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = int32_t(i);
  const auto root = [&](int32_t i) {
    while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
    return i;
  };
  const auto origin = [&](int k, size_t corner) {
    return ids.at(&*solids[size_t(k)].origin[size_t(solids[size_t(k)].mesh.face_vertices[corner])]);
  };
  std::map<std::array<int32_t, 3>, int32_t> first_faces; // sorted corners -> face of solid 0
  for (int32_t f = 0; f < solids[0].mesh.num_faces(); ++f) {
    std::array<int32_t, 3> key{origin(0, size_t(3 * f)), origin(0, size_t(3 * f + 1)), origin(0, size_t(3 * f + 2))};
    std::sort(key.begin(), key.end());
    first_faces.emplace(key, f);
  }
  for (int32_t g = 0; g < solids[1].mesh.num_faces(); ++g) {
    std::array<int32_t, 3> key{origin(1, size_t(3 * g)), origin(1, size_t(3 * g + 1)), origin(1, size_t(3 * g + 2))};
    std::sort(key.begin(), key.end());
    const auto it = first_faces.find(key);
    if (it == first_faces.end()) continue;
    for (size_t j = 0; j < 3; ++j)
      for (size_t i = 0; i < 3; ++i)
        if (origin(0, size_t(3 * it->second) + i) == origin(1, size_t(3 * g) + j)) {
          const int32_t a = root(fans[0][size_t(3 * it->second) + i]), b = root(int32_t(offset) + fans[1][size_t(3 * g) + j]);
          parent[size_t(std::max(a, b))] = std::min(a, b);
        }
  }
  // Every corner of both solids: its triangulation vertex, its fan's class, its fan.
  struct Corner {
    int32_t vertex, group, fan, corner;
    int k;
    bool operator<(const Corner& o) const { return std::tie(vertex, group, k, fan, corner) < std::tie(o.vertex, o.group, o.k, o.fan, o.corner); }
  };
  std::vector<Corner> corners;
  for (int k = 0; k < 2; ++k)
    for (size_t c = 0; c < fans[size_t(k)].size(); ++c) {
      const int32_t node = int32_t(size_t(k) * offset) + fans[size_t(k)][c];
      corners.push_back({origin(k, c), root(node), node, int32_t(c), k});
    }
  std::sort(corners.begin(), corners.end());
  // Where each moved fan's corner goes.
  std::unordered_map<int32_t, Vec3d> target; // node -> position
  const auto far = [&](const Corner& c) {
    const PolygonMesh& m = solids[size_t(c.k)].mesh;
    return to_double(m.positions[size_t(m.face_vertices[size_t(c.corner - c.corner % 3 + (c.corner + 1) % 3)])]);
  };
  const auto move = [&](std::span<const Corner> group) { // all fans of `group` to one place
    Vec3d sum{};
    for (const Corner& c : group) sum = sum + far(c);
    const PolygonMesh& m = solids[size_t(group[0].k)].mesh;
    const Vec3d p = to_double(m.positions[size_t(m.face_vertices[size_t(group[0].corner)])]);
    const Vec3d q = p + (sum * (1.0 / double(group.size())) - p) * (1.0 / 20);
    for (const Corner& c : group) target[c.fan] = q;
  };
  for (size_t i = 0, j; i < corners.size(); i = j) {
    j = i;
    while (j < corners.size() && corners[j].vertex == corners[i].vertex) ++j;
    const std::span<const Corner> star(corners.data() + i, j - i);
    const auto fans_differ = [](const Corner& a, const Corner& b) { return a.fan != b.fan; };
    if (std::adjacent_find(star.begin(), star.end(), fans_differ) == star.end()) continue; // one fan
    for (size_t g = 0, h; g < star.size(); g = h) {
      h = g;
      while (h < star.size() && star[h].group == star[g].group) ++h;
      const std::span<const Corner> group = star.subspan(g, h - g);
      bool alone = false; // two fans of one solid in the group
      for (size_t e = 1; e < group.size(); ++e) alone |= group[e].k == group[e - 1].k && group[e].fan != group[e - 1].fan;
      if (!alone) {
        if (h - g < star.size()) move(group);
        continue;
      }
      for (size_t e = 1; e < group.size(); ++e)
        if (group[e].k == group[e - 1].k && group[e].fan != group[e - 1].fan) {
          const Corner& c = group[e];
          unparted.emplace_back(solids[size_t(c.k)].origin[size_t(solids[size_t(c.k)].mesh.face_vertices[size_t(c.corner)])], c.k + 1);
          break;
        }
    }
  }
  if (!unparted.empty()) return unparted;
  // Each solid: the first fan round a vertex keeps it, the others get new ones.
  for (int k = 0; k < 2; ++k) {
    PolygonMesh& m = solids[size_t(k)].mesh;
    std::unordered_map<int32_t, int32_t> vertex_of; // node -> vertex
    std::vector<uint8_t> kept(m.positions.size(), 0);
    for (size_t c = 0; c < fans[size_t(k)].size(); ++c) {
      const int32_t node = int32_t(size_t(k) * offset) + fans[size_t(k)][c];
      const auto to = target.find(node);
      if (to == target.end()) continue;
      int32_t& v = m.face_vertices[c];
      const auto [it, fresh] = vertex_of.emplace(node, v);
      if (fresh && kept[size_t(v)]) {
        it->second = int32_t(m.positions.size());
        m.positions.push_back({});
        solids[size_t(k)].origin.push_back(solids[size_t(k)].origin[size_t(v)]);
      }
      kept[size_t(v)] = 1;
      v = it->second;
    }
    for (const auto& [node, v] : vertex_of) {
      const Vec3d q = target.at(node);
      m.positions[size_t(v)] = {float(q.x), float(q.y), float(q.z)};
    }
  }
  return unparted;
}

} // namespace

SplitShell sampled_shell(const PaintedSurface& s, double wall, double clearance) {
  const bool apart = clearance > 0;
  const Normals n = normals_of(s);
  const Labels labels(s, n, wall, clearance);
  Vec3d low{INFINITY, INFINITY, INFINITY}, high = low * -1;
  for (const Vec3 p : s.positions) {
    low = {std::min(low.x, double(p.x)), std::min(low.y, double(p.y)), std::min(low.z, double(p.z))};
    high = {std::max(high.x, double(p.x)), std::max(high.y, double(p.y)), std::max(high.z, double(p.z))};
  }
  const double margin = 2 * wall;
  const double radius = norm(high - low) / 2 + margin;
  CGAL::Random random(0);
  const std::function<int(const Point&)> label = std::cref(labels);
  Domain domain(label, CGAL::Bbox_3(low.x - margin, low.y - margin, low.z - margin, high.x + margin, high.y + margin, high.z + margin),
                0.01 * wall / radius, CGAL::Null_subdomain_index(), &random);
  const std::vector<std::vector<Point>> features = features_of(s, n, !apart);
  domain.add_features(features.begin(), features.end());
  namespace p = CGAL::parameters;
  // Facets about a wall across (finer only where the surface curves), within a tenth of
  // a wall of it; the points found on the surface within a hundredth of a wall.
  const Criteria criteria(p::facet_angle = 25, p::facet_size = wall, p::facet_distance = 0.1 * wall,
                          p::cell_radius_edge_ratio = 3, p::cell_size = wall);
  // With a clearance, cells as small as it in and near the gap (within about 1.5 of it of
  // where the solids would meet), so that the gap is cells wide, and facets within a tenth
  // of it of the gap's walls (the curved outside near the cut, more costly to follow that
  // closely and moving no wall sideways, within a quarter).
  const auto near = [&labels, clearance](const Point& x) { return labels.near_cut(x, 1.5 * clearance); };
  const auto size = [near, wall, clearance](const Point& x, int, const Domain::Index&) { return near(x) >= 0 ? clearance : wall; };
  const auto distance = [near, wall, clearance](const Point& x, int, const Domain::Index&) {
    const double depth = near(x);
    return depth < 0 ? 0.1 * wall : depth < 0.25 * clearance ? 0.25 * clearance : 0.1 * clearance;
  };
  const Criteria apart_criteria(p::facet_angle = 25, p::facet_size = size, p::facet_distance = distance,
                                p::cell_radius_edge_ratio = 3, p::cell_size = size);
  C3t3 c3t3;
  // The kept edges protected by balls half a wall across, down to a sixteenth of one where
  // they come near each other (without that floor, edges that nearly touch are protected
  // by ever smaller balls, for hours).
  const auto edge_size = [&](const Point&, int, const Domain::Index&) { return wall / 2; };
  CGAL::Mesh_3::Protect_edges_sizing_field<C3t3, Domain, decltype(edge_size)>(c3t3, domain, edge_size, wall / 16)();
  seed(c3t3, domain, s, n, wall, wall);
  CGAL::refine_mesh_3(c3t3, domain, apart ? apart_criteria : criteria, p::no_perturb(), p::no_exude(), p::no_reset_c3t3());
  // The cells' labels mended until each solid's boundary, and the shell's, is a closed
  // surface: along edges and at corners of the shell's surface, and at corners where a
  // solid's cones would stay joined by the other's, by relabelling; at the other corners,
  // by parting the cones.
  const std::array<size_t, 2> pieces = pieces_of(s, n, wall * wall);
  std::array<Boundary, 2> solids;
  for (int round = 0;; ++round) {
    for (int pass = 0; pass < 8; ++pass)
      if (!((apart && separate(c3t3)) | drop_crumbs(c3t3, pieces, apart) | fill_outside_tips(c3t3, apart) | unpinch(c3t3, apart)))
        break;
    for (int k = 0; k < 2; ++k) {
      solids[size_t(k)] = boundary_of(c3t3, 2u << k);
      const PolygonMesh& solid = solids[size_t(k)].mesh;
      if (solid.num_faces() == 0) throw TopologyError("shell: colour region " + std::to_string(k + 1) + " has no wall");
      if (!closed(solid))
        throw TopologyError("shell: the sampled solid of colour region " + std::to_string(k + 1) +
                            " touches itself along an edge (a thinner --shell may not)");
    }
    std::unordered_map<const void*, int32_t> ids;
    for (auto v = c3t3.triangulation().finite_vertices_begin(); v != c3t3.triangulation().finite_vertices_end(); ++v)
      ids.emplace(&*v, int32_t(ids.size()));
    const std::vector<std::pair<Tr::Vertex_handle, int>> unparted = part_pinched_corners(solids, ids);
    if (unparted.empty()) break;
    if (round == 8) {
      const Point& at = unparted[0].first->point().point();
      throw TopologyError("shell: the sampled solid of colour region " + std::to_string(unparted[0].second) + " still touches itself near " +
                          place(to_float({at.x(), at.y(), at.z()})) + " (a thinner --shell may not)");
    }
    // The solid's cones join across the other's cells round the corner.
    for (const auto& [v, k] : unparted) {
      std::vector<Tr::Cell_handle> star;
      c3t3.triangulation().incident_cells(v, std::back_inserter(star));
      for (const Tr::Cell_handle c : star)
        if (label_of(c3t3, c) == 3 - k) set_label(c3t3, c, k, apart);
    }
  }
  SplitShell out;
  for (int k = 0; k < 2; ++k) {
    PolygonMesh& solid = solids[size_t(k)].mesh;
    if (const std::vector<int32_t> crossing = self_intersecting_faces(solid); !crossing.empty())
      throw TopologyError("shell: the sampled wall of colour region " + std::to_string(k + 1) + " crosses itself near " +
                          place(solid.positions[size_t(solid.face(crossing[0])[0])]));
    out.volumes[size_t(k)] = volume_of(solid);
    out.solids[size_t(k)] = std::move(solid);
  }
  if (apart) {
    measure_apart(out, 0);
    if (out.apart < 0.45 * clearance)
      throw TopologyError("shell: the sampled pieces come within " + std::to_string(out.apart) + " of each other near " +
                          place(out.apart_at) + ", less than 0.45 of the clearance (a wider --clearance may not)");
  }
  out.thinnest = wall;
  out.sampled = true;
  return out;
}

} // namespace meander
