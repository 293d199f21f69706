// The only file that includes CGAL, so that its templates are compiled once.
#include "cgal_judge.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <vector>

namespace meander::test {

CgalVerdict cgal_judge(const PolygonMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  namespace PMP = CGAL::Polygon_mesh_processing;
  Mesh m;
  std::vector<Mesh::Vertex_index> vertex;
  vertex.reserve(mesh.positions.size());
  for (const Vec3& p : mesh.positions) vertex.push_back(m.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
  CgalVerdict verdict;
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const std::span<const int32_t> v = mesh.face(f);
    for (size_t k = 1; k + 1 < v.size(); ++k)
      if (m.add_face(vertex[size_t(v[0])], vertex[size_t(v[k])], vertex[size_t(v[k + 1])]) == Mesh::null_face())
        return verdict;
  }
  verdict.loaded = true;
  verdict.closed = CGAL::is_closed(m);
  verdict.self_intersecting = PMP::does_self_intersect(m);
  if (verdict.closed) {
    verdict.volume = PMP::volume(m);
    verdict.outward = PMP::is_outward_oriented(m);
  }
  return verdict;
}

double cgal_least_distance(const PolygonMesh& from, const PolygonMesh& to) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Kernel::Triangle_3>::const_iterator>;
  const auto point = [](Vec3 p) { return Kernel::Point_3(p.x, p.y, p.z); };
  std::vector<Kernel::Triangle_3> triangles;
  for (int32_t f = 0; f < to.num_faces(); ++f) {
    const std::span<const int32_t> v = to.face(f);
    for (size_t k = 1; k + 1 < v.size(); ++k)
      triangles.emplace_back(point(to.positions[size_t(v[0])]), point(to.positions[size_t(v[k])]), point(to.positions[size_t(v[k + 1])]));
  }
  CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>> tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  double least = INFINITY;
  for (int32_t f = 0; f < from.num_faces(); ++f) {
    const std::span<const int32_t> v = from.face(f);
    for (size_t k = 0; k < v.size(); ++k) {
      const Vec3 a = from.positions[size_t(v[k])], b = from.positions[size_t(v[(k + 1) % v.size()])];
      for (const Vec3 p : {a, (a + b) * 0.5f}) least = std::min(least, std::sqrt(tree.squared_distance(point(p))));
    }
  }
  return least;
}

} // namespace meander::test
