#include "meander/remesh.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <tbb/parallel_for.h>

#include <vector>

namespace meander {

void project_onto_surface(const PolygonMesh& surface, std::span<Vec3> points) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Triangle = Kernel::Triangle_3;
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  if (points.empty() || surface.num_faces() == 0) return;
  auto point = [&surface](int32_t v) {
    const Vec3 p = surface.positions[size_t(v)];
    return Kernel::Point_3(p.x, p.y, p.z);
  };
  std::vector<Triangle> triangles; // the polygons as fans, as the writers triangulate them
  for (int32_t f = 0; f < surface.num_faces(); ++f) {
    const std::span<const int32_t> face = surface.face(f);
    for (size_t i = 1; i + 1 < face.size(); ++i)
      triangles.emplace_back(point(face[0]), point(face[i]), point(face[i + 1]));
  }
  Tree tree(triangles.begin(), triangles.end());
  // Built here, before the threads query it: the tree builds lazily otherwise.
  tree.build();
  tree.accelerate_distance_queries();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const Vec3 p = points[i];
      const Kernel::Point_3 q = tree.closest_point(Kernel::Point_3(p.x, p.y, p.z));
      points[i] = {float(q.x()), float(q.y()), float(q.z())};
    }
  });
}

} // namespace meander
