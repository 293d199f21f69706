// Core types: the polygon mesh that readers and writers speak, and closed polylines.
// Plain structs of flat arrays with int32 index handles; no pointers between elements.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace meander {

// One vector type in two precisions. Positions are Vec3 (float): every common mesh
// format stores float32, and it halves the memory of the largest arrays. Geometry whose
// results must not depend on float rounding (printability's exact signs, the renderer's
// camera, subdivision's deep levels) works in Vec3d, to which every Vec3 converts exactly.
template <class T> struct Vec3T {
  T x = 0, y = 0, z = 0;

  friend Vec3T operator+(Vec3T a, Vec3T b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend Vec3T operator-(Vec3T a, Vec3T b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend Vec3T operator*(Vec3T a, T s) { return {a.x * s, a.y * s, a.z * s}; }
  friend Vec3T operator*(T s, Vec3T a) { return a * s; }
  friend bool operator==(Vec3T a, Vec3T b) = default;
};
using Vec3 = Vec3T<float>;
using Vec3d = Vec3T<double>;

inline Vec3d to_double(Vec3 p) { return {p.x, p.y, p.z}; }
inline Vec3 to_float(Vec3d p) { return {float(p.x), float(p.y), float(p.z)}; }

// Products in double whatever T is.
template <class T> double dot(Vec3T<T> a, Vec3T<T> b) { return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z; }
template <class T> Vec3T<T> cross(Vec3T<T> a, Vec3T<T> b) {
  return {T(double(a.y) * b.z - double(a.z) * b.y), T(double(a.z) * b.x - double(a.x) * b.z),
          T(double(a.x) * b.y - double(a.y) * b.x)};
}
template <class T> double norm(Vec3T<T> a) { return std::sqrt(dot(a, a)); }
template <class T> bool is_finite(Vec3T<T> a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

struct Box3 {
  Vec3 min{INFINITY, INFINITY, INFINITY};
  Vec3 max{-INFINITY, -INFINITY, -INFINITY};
  void extend(Vec3 p);
  bool empty() const { return min.x > max.x; }
  double diagonal() const { return empty() ? 0.0 : norm(max - min); }
  double largest_side() const {
    return empty() ? 0.0 : std::max({double(max.x) - min.x, double(max.y) - min.y, double(max.z) - min.z});
  }
};
Box3 bounding_box(std::span<const Vec3> points);

// A polygon mesh: positions plus faces in CSR form. Face f has the vertices
// face_vertices[face_start[f] .. face_start[f+1]); face_start has num_faces()+1 entries
// and starts with 0. Corner c = face_start[f] + i is also the halfedge from vertex i
// to vertex i+1 (cyclically) of face f.
struct PolygonMesh {
  std::vector<Vec3> positions;
  std::vector<int32_t> face_start{0};
  std::vector<int32_t> face_vertices;

  int32_t num_vertices() const { return int32_t(positions.size()); }
  int32_t num_faces() const { return int32_t(face_start.size()) - 1; }
  int32_t num_corners() const { return int32_t(face_vertices.size()); }
  int32_t face_size(int32_t f) const { return face_start[f + 1] - face_start[f]; }
  std::span<const int32_t> face(int32_t f) const {
    return {face_vertices.data() + face_start[f], size_t(face_size(f))};
  }
  void add_face(std::span<const int32_t> vertices) {
    face_vertices.insert(face_vertices.end(), vertices.begin(), vertices.end());
    face_start.push_back(int32_t(face_vertices.size()));
  }
  void add_face(std::initializer_list<int32_t> vertices) { add_face(std::span(vertices.begin(), vertices.size())); }
};

// The mean of a face's corners, `face` indexing `positions` (in double, rounded once).
Vec3 centroid(std::span<const Vec3> positions, std::span<const int32_t> face);

// Removes the faces f with remove[f] set, keeping the others' order. O(corners).
void remove_faces(PolygonMesh& mesh, std::span<const uint8_t> remove);

// Keeps the vertices v with keep[v] set, in their order, and renumbers the faces' corners
// (every corner must be a kept vertex). Returns each old vertex's new index, -1 for
// those dropped. O(vertices + corners).
std::vector<int32_t> keep_vertices(PolygonMesh& mesh, std::span<const uint8_t> keep);

// Area-weighted vertex normals of the polygons fanned from their first vertex, unit
// length; a vertex without area around it gets +z (glTF requires unit normals). GLB
// files and the studio's view shade with them.
std::vector<Vec3> vertex_normals(const PolygonMesh& mesh);

// Polylines (the curves): polyline k has the points points[start[k] .. start[k+1]) and
// closes back to its first point unless open[k] is set. `open` is empty when every
// polyline is closed, as the curves Meander makes are; readers of files that hold open
// polylines (PLY edge chains, OBJ `l` elements that do not come back) give one flag each.
struct Polylines {
  std::vector<Vec3> points;
  std::vector<int32_t> start{0};
  std::vector<uint8_t> open;

  int32_t size() const { return int32_t(start.size()) - 1; }
  bool closed(int32_t k) const { return open.empty() || open[k] == 0; }
  std::span<const Vec3> polyline(int32_t k) const {
    return {points.data() + start[k], size_t(start[k + 1] - start[k])};
  }
};

// The curves' total length, a closed curve's closing segment included. O(points).
double total_length(const Polylines& curves);

} // namespace meander
