// The only file that includes CGAL, so that its templates are compiled once.
#include "cgal_judge.h"

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

} // namespace meander::test
