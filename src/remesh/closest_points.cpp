#include "meander/closest_points.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

namespace meander {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;

} // namespace

struct ClosestPoints::Tree {
  std::vector<Triangle> triangles;
  CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>> tree;
};

ClosestPoints::ClosestPoints(const PolygonMesh& surface) : tree_(std::make_unique<Tree>()) {
  auto point = [&surface](int32_t v) {
    const Vec3 p = surface.positions[size_t(v)];
    return Kernel::Point_3(p.x, p.y, p.z);
  };
  for (int32_t f = 0; f < surface.num_faces(); ++f) {
    const std::span<const int32_t> face = surface.face(f);
    for (size_t i = 1; i + 1 < face.size(); ++i)
      tree_->triangles.emplace_back(point(face[0]), point(face[i]), point(face[i + 1]));
  }
  if (tree_->triangles.empty()) return;
  tree_->tree.insert(tree_->triangles.begin(), tree_->triangles.end());
  // Built here, before threads query it: the tree builds lazily otherwise.
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
}

ClosestPoints::~ClosestPoints() = default;
ClosestPoints::ClosestPoints(ClosestPoints&&) noexcept = default;
ClosestPoints& ClosestPoints::operator=(ClosestPoints&&) noexcept = default;

Vec3d ClosestPoints::closest(Vec3d p) const {
  if (tree_->triangles.empty()) return p;
  const Kernel::Point_3 q = tree_->tree.closest_point(Kernel::Point_3(p.x, p.y, p.z));
  return {q.x(), q.y(), q.z()};
}

namespace {

ClosestPoints::Hit hit(const std::pair<Kernel::Point_3, std::vector<Triangle>::const_iterator>& found,
                       const std::vector<Triangle>& triangles) {
  const auto& [q, triangle] = found;
  const Kernel::Vector_3 n = CGAL::normal(triangle->vertex(0), triangle->vertex(1), triangle->vertex(2));
  const double length = std::sqrt(n.squared_length());
  const Vec3d normal = length > 0 ? Vec3d{n.x() / length, n.y() / length, n.z() / length} : Vec3d{};
  return {{q.x(), q.y(), q.z()}, normal, int32_t(triangle - triangles.begin())};
}

} // namespace

ClosestPoints::Hit ClosestPoints::closest_hit(Vec3d p) const {
  if (tree_->triangles.empty()) return {p, {}};
  return hit(tree_->tree.closest_point_and_primitive(Kernel::Point_3(p.x, p.y, p.z)), tree_->triangles);
}

ClosestPoints::Hit ClosestPoints::closest_hit(Vec3d p, const Hit& hint) const {
  if (hint.triangle < 0 || size_t(hint.triangle) >= tree_->triangles.size()) return closest_hit(p);
  const Kernel::Point_3 near(hint.point.x, hint.point.y, hint.point.z);
  return hit(tree_->tree.closest_point_and_primitive(Kernel::Point_3(p.x, p.y, p.z),
                                                     {near, tree_->triangles.cbegin() + hint.triangle}),
             tree_->triangles);
}

void ClosestPoints::project(std::span<Vec3> points, std::span<Vec3> normals) const {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      if (normals.empty()) {
        points[i] = to_float(closest(to_double(points[i])));
        continue;
      }
      const Hit hit = closest_hit(to_double(points[i]));
      points[i] = to_float(hit.point);
      normals[i] = to_float(hit.normal);
    }
  });
}

} // namespace meander
