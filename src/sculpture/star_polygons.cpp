#include "meander/star_polygons.h"

namespace meander {

StarredPolygons star_polygons(PolygonMesh mesh, int min_sides) {
  StarredPolygons result;
  int64_t extra_corners = 0;
  for (int32_t f = 0; f < mesh.num_faces(); ++f)
    if (mesh.face_size(f) >= min_sides) {
      ++result.stars;
      extra_corners += 2 * int64_t(mesh.face_size(f));
    }
  if (result.stars == 0) {
    result.mesh = std::move(mesh);
    return result;
  }
  PolygonMesh& out = result.mesh;
  out.positions = std::move(mesh.positions);
  out.positions.reserve(out.positions.size() + size_t(result.stars));
  out.face_vertices.reserve(mesh.face_vertices.size() + size_t(extra_corners));
  for (int32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto face = mesh.face(f);
    if (int32_t(face.size()) < min_sides) {
      out.add_face(face);
      continue;
    }
    const int32_t centre = out.num_vertices();
    out.positions.push_back(centroid(out.positions, face));
    for (size_t k = 0; k < face.size(); ++k) out.add_face({centre, face[k], face[(k + 1) % face.size()]});
  }
  return result;
}

} // namespace meander
