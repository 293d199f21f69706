#include "meander/shapes.h"

#include "meander/error.h"
#include "meander/locality.h"
#include "meander/subdivide.h"
#include "core/random.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

namespace meander {

namespace {

constexpr double pi = std::numbers::pi;

// Two triangles per quad of a (rows x cols) vertex-grid patch, given the index of
// grid point (i, j); the diagonal alternates in a checkerboard so no direction is
// favoured.
template <typename Index>
void triangulate_grid(PolygonMesh& m, int rows, int cols, Index index) {
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const int32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.add_face({a, b, c});
        m.add_face({a, c, d});
      } else {
        m.add_face({a, b, d});
        m.add_face({b, c, d});
      }
    }
}

int side_for(int64_t faces, double factor, int minimum) {
  return std::max(minimum, int(std::lround(std::sqrt(double(faces) / factor))));
}

} // namespace

PolygonMesh sphere(int64_t faces) {
  // rings x 2*rings quads minus the two polar rows of triangles: about 4 rings^2 triangles.
  const int rings = side_for(faces, 4, 2), segments = 2 * rings;
  PolygonMesh m;
  m.positions.push_back({0, 0, 1});
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = pi * i / rings, phi = 2 * pi * j / segments;
      m.positions.push_back({float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))});
    }
  m.positions.push_back({0, 0, -1});
  const int32_t south = int32_t(m.positions.size()) - 1;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) m.add_face({0, ring(1, j), ring(1, j + 1)});
  triangulate_grid(m, rings - 2, segments, [&](int i, int j) { return ring(i + 1, j); });
  for (int j = 0; j < segments; ++j) m.add_face({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
  return m;
}

PolygonMesh torus(int64_t faces) {
  const int minor = side_for(faces, 4, 3), major = 2 * minor;
  PolygonMesh m;
  for (int i = 0; i < major; ++i)
    for (int j = 0; j < minor; ++j) {
      const double u = 2 * pi * i / major, v = 2 * pi * j / minor, r = 1 + 0.35 * std::cos(v);
      m.positions.push_back({float(r * std::cos(u)), float(r * std::sin(u)), float(0.35 * std::sin(v))});
    }
  triangulate_grid(m, major, minor, [&](int i, int j) { return (i % major) * minor + (j % minor); });
  return m;
}

PolygonMesh genus_surface(int genus, int64_t faces) {
  if (genus < 0) throw UsageError("genus must be >= 0 (got " + std::to_string(genus) + ")");
  // The boundary of a slab of (2g+1) x 3 x 1 unit cubes with g cubes taken out of the
  // middle row: every edge of it is shared by exactly two squares, so it is a closed
  // manifold of genus g, and its Catmull-Clark limit is a smooth rounded pretzel.
  const int width = 2 * genus + 1, depth = 3;
  auto solid = [&](int i, int j, int k) {
    return i >= 0 && i < width && j >= 0 && j < depth && k == 0 && !(j == 1 && i % 2 == 1);
  };
  auto lattice = [&](int i, int j, int k) { return int32_t(i + (width + 1) * (j + (depth + 1) * k)); };
  PolygonMesh coarse;
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= depth; ++j)
      for (int i = 0; i <= width; ++i) coarse.positions.push_back({float(i), float(j), float(k) * 1.2f});
  for (int i = 0; i < width; ++i)
    for (int j = 0; j < depth; ++j) {
      if (!solid(i, j, 0)) continue;
      for (int axis = 0; axis < 3; ++axis)
        for (int sign : {-1, 1}) {
          int cell[3] = {i, j, 0};
          cell[axis] += sign;
          if (solid(cell[0], cell[1], cell[2])) continue;
          // The square on that side, wound so its normal e_b x e_c = e_axis points out.
          int base[3] = {i, j, 0};
          base[axis] += sign > 0;
          const int b = (axis + 1) % 3, c = (axis + 2) % 3;
          int p[4][3];
          for (int corner = 0; corner < 4; ++corner) {
            std::copy(base, base + 3, p[corner]);
            p[corner][b] += corner == 1 || corner == 2;
            p[corner][c] += corner >= 2;
          }
          int32_t q[4];
          for (int corner = 0; corner < 4; ++corner) q[corner] = lattice(p[corner][0], p[corner][1], p[corner][2]);
          if (sign > 0) coarse.add_face({q[0], q[1], q[2], q[3]});
          else coarse.add_face({q[3], q[2], q[1], q[0]});
        }
    }
  // Drop the lattice points no square uses.
  std::vector<int32_t> remap(coarse.positions.size(), -1);
  PolygonMesh compact;
  for (int32_t& v : coarse.face_vertices) {
    if (remap[size_t(v)] < 0) {
      remap[size_t(v)] = int32_t(compact.positions.size());
      compact.positions.push_back(coarse.positions[size_t(v)]);
    }
    v = remap[size_t(v)];
  }
  compact.face_vertices = std::move(coarse.face_vertices);
  compact.face_start = std::move(coarse.face_start);

  // Each level multiplies the quads by 4; pick the level nearest the target in log scale.
  const double target_quads = std::max<double>(1, double(faces) / 2);
  int levels = 0;
  while (levels < 12 && std::abs(std::log(compact.num_faces() * std::pow(4.0, levels + 1) / target_quads)) <
                           std::abs(std::log(compact.num_faces() * std::pow(4.0, levels) / target_quads)))
    ++levels;
  const PolygonMesh quads = subdivide(compact, {.levels = levels, .limit = true});

  PolygonMesh m;
  m.positions = quads.positions;
  m.face_vertices.reserve(size_t(quads.num_faces()) * 6);
  m.face_start.reserve(size_t(quads.num_faces()) * 2 + 1);
  for (int32_t f = 0; f < quads.num_faces(); ++f) {
    const auto v = quads.face(f);
    const double d02 = norm(m.positions[size_t(v[0])] - m.positions[size_t(v[2])]);
    const double d13 = norm(m.positions[size_t(v[1])] - m.positions[size_t(v[3])]);
    if (d02 <= d13) {
      m.add_face({v[0], v[1], v[2]});
      m.add_face({v[0], v[2], v[3]});
    } else {
      m.add_face({v[0], v[1], v[3]});
      m.add_face({v[1], v[2], v[3]});
    }
  }
  return m;
}

PolygonMesh grid(int64_t faces) {
  const int n = side_for(faces, 2, 1);
  PolygonMesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) m.positions.push_back({float(i) / float(n), float(j) / float(n), 0});
  triangulate_grid(m, n, n, [&](int i, int j) { return i * (n + 1) + j; });
  return m;
}

PolygonMesh moebius(int64_t faces) {
  const int across = std::max(1, int(std::lround(std::sqrt(double(faces) / 8)))), around = std::max(3, 8 * across);
  PolygonMesh m;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j <= across; ++j) {
      const double u = 2 * pi * i / around, v = (double(j) / across - 0.5) * 0.8;
      const double r = 1 + v * std::cos(u / 2);
      m.positions.push_back({float(r * std::cos(u)), float(r * std::sin(u)), float(v * std::sin(u / 2))});
    }
  auto index = [&](int i, int j) { return int32_t(i * (across + 1) + j); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      // After a full turn the strip comes back flipped: column j meets column across-j.
      const bool wrap = i + 1 == around;
      const int32_t c = wrap ? index(0, across - (j + 1)) : index(i + 1, j + 1);
      const int32_t b = wrap ? index(0, across - j) : index(i + 1, j);
      m.add_face({index(i, j), b, c, index(i, j + 1)});
    }
  return m;
}

PolygonMesh make_shape(std::string_view name, int64_t faces, int genus) {
  if (faces < 1) throw ParameterError("faces", " must be at least 1 (got " + std::to_string(faces) + ")");
  if (faces > 500'000'000) throw ParameterError("faces", " must be at most 500000000 (got " + std::to_string(faces) + ")");
  if (name == "sphere") return sphere(faces);
  if (name == "torus") return torus(faces);
  if (name == "pretzel") return genus_surface(2, faces);
  if (name == "genus") return genus_surface(genus, faces);
  if (name == "grid") return grid(faces);
  if (name == "moebius") return moebius(faces);
  throw UsageError("unknown shape '" + std::string(name) + "' (expected sphere, torus, pretzel, genus, grid or moebius)");
}

PolygonMesh shuffled(const PolygonMesh& mesh, uint64_t seed) {
  Random random(seed);
  const auto permutation = [&](int32_t n) { // Fisher-Yates
    std::vector<int32_t> p(static_cast<size_t>(n));
    std::iota(p.begin(), p.end(), 0);
    for (int32_t i = n - 1; i > 0; --i) std::swap(p[size_t(i)], p[size_t(random.below(uint32_t(i) + 1))]);
    return p;
  };
  MeshOrder order;
  order.vertex_rank = permutation(mesh.num_vertices());
  order.face_order = permutation(mesh.num_faces());
  return reordered(mesh, order);
}

} // namespace meander
