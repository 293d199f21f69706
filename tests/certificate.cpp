#include "certificate.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace meander::test {

ObjGroups parse_obj_groups(const std::filesystem::path& path) {
  ObjGroups obj;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") {
      std::array<double, 3> p{};
      ss >> p[0] >> p[1] >> p[2];
      obj.vertices.push_back(p);
    } else if (tag == "o") {
      obj.groups.emplace_back();
    } else if (tag == "f") {
      if (obj.groups.empty()) obj.groups.emplace_back();
      std::array<int, 3> t{};
      ss >> t[0] >> t[1] >> t[2];
      for (int& v : t) v -= 1;
      obj.groups.back().push_back(t);
    } else if (tag == "l") {
      std::vector<int> l;
      for (int v; ss >> v;) l.push_back(v - 1);
      obj.lines.push_back(l);
    }
  }
  return obj;
}

CertificateFacts check_certificate(const ObjGroups& c) {
  CertificateFacts facts;
  facts.cycles = int(c.groups.size());
  auto fail = [&](const std::string& why) {
    if (facts.problem.empty()) facts.problem = why;
  };
  std::vector<std::array<int, 3>> sorted_triangles;
  std::vector<std::array<int, 3>> edges; // (lo, hi, group), sorted below
  for (size_t g = 0; g < c.groups.size(); ++g) {
    const auto& tris = c.groups[g];
    if (tris.size() < 2) fail("group " + std::to_string(g) + " has fewer than 2 triangles");
    for (size_t i = 0; i < tris.size(); ++i) {
      auto key = tris[i];
      std::sort(key.begin(), key.end());
      sorted_triangles.push_back(key);
      for (int k = 0; k < 3; ++k) {
        const int a = tris[i][size_t(k)], b = tris[i][size_t((k + 1) % 3)];
        edges.push_back({std::min(a, b), std::max(a, b), int(g)});
      }
      const auto& next = tris[(i + 1) % tris.size()];
      int shared = 0;
      for (int v : tris[i]) shared += std::count(next.begin(), next.end(), v) > 0;
      if (shared < 2)
        fail("triangles " + std::to_string(i) + " and " + std::to_string((i + 1) % tris.size()) + " of group " +
             std::to_string(g) + " share no edge");
    }
    facts.triangles += long(tris.size());
  }
  std::sort(sorted_triangles.begin(), sorted_triangles.end());
  if (std::adjacent_find(sorted_triangles.begin(), sorted_triangles.end()) != sorted_triangles.end())
    fail("a triangle appears twice");
  std::sort(edges.begin(), edges.end());
  std::vector<int> used;
  long unique_edges = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
    ++unique_edges;
    used.push_back(edges[i][0]);
    used.push_back(edges[i][1]);
    if (j - i > 2) fail("an edge has more than two triangles");
    if (j - i == 1) ++facts.boundary_edges;
    if (j - i == 2 && edges[i][2] != edges[i + 1][2]) fail("two cycles share an edge (a missed merge)");
    i = j;
  }
  std::sort(used.begin(), used.end());
  const long vertices = long(std::unique(used.begin(), used.end()) - used.begin());
  facts.euler_characteristic = vertices - unique_edges + facts.triangles;
  return facts;
}

namespace {

using P = std::array<double, 3>;
P sub(P a, P b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(P a, P b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
double point_triangle_distance(P p, P a, P b, P c) {
  const P ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  auto at = [&](double v, double w) {
    const P q{a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w};
    const P d = sub(p, q);
    return std::sqrt(dot(d, d));
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return at(0, 0);
  const P bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return at(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return at(d1 / (d1 - d3), 0);
  const P cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return at(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w);
  }
  const double denom = 1 / (va + vb + vc);
  return at(vb * denom, vc * denom);
}

} // namespace

double curve_distance_ratio(const ObjGroups& curve, const ObjGroups& cert) {
  if (curve.lines.size() != cert.groups.size()) return 1e300;
  double worst = 0;
  for (size_t g = 0; g < cert.groups.size(); ++g) {
    const auto& tris = cert.groups[g];
    const std::vector<int>& line = curve.lines[g];
    const size_t n = tris.size(), points = line.size() - 1; // the closing index repeats the first
    if (n == 0 || points % n != 0) return 1e300;
    const size_t samples = points / n;
    for (size_t j = 0; j < points; ++j) {
      // Sample j lies on the spline segment of control points i and i+1, a blend of the
      // control points i-1 .. i+2, which lie in those triangles of the cycle.
      const size_t i = j / samples;
      const P p = curve.vertices[size_t(line[j])];
      double best = 1e300, longest = 0;
      for (size_t d = 0; d < 4; ++d) {
        const auto& t = tris[(i + n + d - 1) % n];
        const P a = cert.vertices[size_t(t[0])], b = cert.vertices[size_t(t[1])], c = cert.vertices[size_t(t[2])];
        best = std::min(best, point_triangle_distance(p, a, b, c));
        for (auto [u, v] : {std::pair{a, b}, {b, c}, {c, a}}) longest = std::max(longest, std::sqrt(dot(sub(u, v), sub(u, v))));
      }
      worst = std::max(worst, best / std::max(longest, 1e-12));
    }
  }
  return worst;
}

} // namespace meander::test
