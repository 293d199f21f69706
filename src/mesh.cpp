#include "meander/mesh.h"

#include <algorithm>

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

} // namespace meander
