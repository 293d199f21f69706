#include "meander/mesh.h"

#include <algorithm>
#include <array>
#include <utility>

namespace meander {

void Box3::extend(Vec3 p) {
  min = {std::min(min.x, p.x), std::min(min.y, p.y), std::min(min.z, p.z)};
  max = {std::max(max.x, p.x), std::max(max.y, p.y), std::max(max.z, p.z)};
}

Box3 bounding_box(std::span<const Vec3> points) {
  Box3 box;
  for (const Vec3& p : points) box.extend(p);
  return box;
}

Vec3 centroid(std::span<const Vec3> positions, std::span<const int32_t> face) {
  double x = 0, y = 0, z = 0;
  for (const int32_t v : face) {
    const Vec3 p = positions[size_t(v)];
    x += p.x;
    y += p.y;
    z += p.z;
  }
  const double n = double(face.size());
  return {float(x / n), float(y / n), float(z / n)};
}

void remove_faces(PolygonMesh& mesh, std::span<const uint8_t> remove) {
  std::vector<int32_t> start{0}, vertices;
  vertices.reserve(mesh.face_vertices.size());
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    if (remove[size_t(f)]) continue;
    const auto face = mesh.face(f);
    vertices.insert(vertices.end(), face.begin(), face.end());
    start.push_back(int32_t(vertices.size()));
  }
  mesh.face_start = std::move(start);
  mesh.face_vertices = std::move(vertices);
}

std::vector<int32_t> keep_vertices(PolygonMesh& mesh, std::span<const uint8_t> keep) {
  std::vector<int32_t> index(mesh.positions.size(), -1);
  int32_t kept = 0;
  for (size_t v = 0; v < index.size(); ++v)
    if (keep[v]) {
      mesh.positions[size_t(kept)] = mesh.positions[v];
      index[v] = kept++;
    }
  mesh.positions.resize(size_t(kept));
  for (int32_t& v : mesh.face_vertices) v = index[size_t(v)];
  return index;
}

std::vector<Vec3> vertex_normals(const PolygonMesh& mesh) {
  std::vector<std::array<double, 3>> sum(mesh.positions.size(), {0, 0, 0});
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto face = mesh.face(f);
    for (size_t i = 1; i + 1 < face.size(); ++i) {
      const Vec3 n = cross(mesh.positions[face[i]] - mesh.positions[face[0]], mesh.positions[face[i + 1]] - mesh.positions[face[0]]);
      for (int32_t v : {face[0], face[i], face[i + 1]}) sum[v] = {sum[v][0] + n.x, sum[v][1] + n.y, sum[v][2] + n.z};
    }
  }
  std::vector<Vec3> normals(mesh.positions.size());
  for (size_t v = 0; v < sum.size(); ++v) {
    const double length = std::sqrt(sum[v][0] * sum[v][0] + sum[v][1] * sum[v][1] + sum[v][2] * sum[v][2]);
    normals[v] = length > 0 && std::isfinite(length)
                     ? Vec3{float(sum[v][0] / length), float(sum[v][1] / length), float(sum[v][2] / length)}
                     : Vec3{0, 0, 1};
  }
  return normals;
}

double total_length(const Polylines& curves) {
  double length = 0;
  for (int32_t k = 0; k < curves.size(); ++k) {
    const std::span<const Vec3> line = curves.polyline(k);
    for (size_t i = 0; i + (curves.closed(k) ? 0 : 1) < line.size(); ++i) length += norm(line[(i + 1) % line.size()] - line[i]);
  }
  return length;
}

} // namespace meander
