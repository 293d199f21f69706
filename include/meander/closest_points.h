// Closest points of a surface: where the points of a curve made on a remeshed surface go
// back onto the input (remesh.h, CurveJob::spacing).
#pragma once

#include "meander/mesh.h"

#include <array>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace meander {

// A bounding volume hierarchy (Embree) of a surface's faces, each polygon fanned from its first vertex
// as the writers triangulate it, and the triangles around each vertex (for walks across
// the surface); built once, then queried from any thread.
class ClosestPoints {
public:
  // O(n log n) for n faces. The surface may be empty (then queries leave points alone).
  explicit ClosestPoints(const PolygonMesh& surface);
  ~ClosestPoints();
  ClosestPoints(ClosestPoints&&) noexcept;
  ClosestPoints& operator=(ClosestPoints&&) noexcept;

  // The closest point of the surface to p, in double precision. O(log n) typically.
  Vec3d closest(Vec3d p) const;
  struct Hit {
    Vec3d point;
    Vec3d normal; // of the triangle the point lies on, unit length (zero for a degenerate one)
    int32_t triangle = -1; // which one, for a hint; -1 on an empty surface
  };
  // The same with that triangle's normal. A hit near p (the last one of a point that
  // moves a little) makes the query several times as fast.
  Hit closest_hit(Vec3d p) const;
  Hit closest_hit(Vec3d p, const Hit& hint) const;
  // The closest point no farther from p than `within`; none (triangle -1) when the
  // surface lies farther: only that near a point is looked at.
  Hit closest_hit(Vec3d p, const Hit& hint, double within) const;
  // Whether `near` holds for a triangle with a point within `within` of p, given that
  // triangle's point closest to p and its corners: the triangles are tried in the tree's
  // order until one does. O(log n + k) for k such triangles.
  bool any_near(Vec3d p, double within, const std::function<bool(Vec3d closest, const std::array<Vec3d, 3>& corners)>& near) const;
  // A nearest point of the surface around `from`, for a point that moved a little from
  // it: walked to from from's triangle across edges and vertices to nearer faces, so a
  // few faces are looked at instead of the tree, and the point stays on the part of the
  // surface it was on (not the other side of a thin sheet, nor another face of a concave
  // fold, that is nearer). The closest point where p lies outside a convex surface; also
  // when the walk would be longer than 64 faces, which is left to the tree, or `from`
  // has no triangle. O(faces crossed). Deterministic.
  Hit nearby_hit(Vec3d p, const Hit& from) const;
  // Points about `step` apart, each with the triangle it lies on, along a short way
  // across the surface from a to b (neither included): for consecutive points of a curve
  // that the closest point put on two sides of a part thinner than the spacing, where the
  // segment between them would cut through. The shortest path over the vertices and
  // points about a step apart on the edges, from a's face to b's, within a step of the
  // shortest way on faces larger than a step. Empty when there is none shorter than
  // `longest`. O(N log N) for the N such points whose way through them from a to b could
  // be shorter than `longest`. Deterministic.
  std::vector<Hit> path(const Hit& a, const Hit& b, double step, double longest) const;
  // Moves each point to the closest point of the surface, and sets normals[i] (if
  // `normals` is not empty, as long as `points`) to the normal there: in parallel, and the
  // same result whatever the number of threads.
  void project(std::span<Vec3> points, std::span<Vec3> normals = {}) const;

private:
  Hit hit_on(int32_t triangle, Vec3d point) const;
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

} // namespace meander
