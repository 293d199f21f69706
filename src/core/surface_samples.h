// Area-weighted random points of a surface: where the evenness measure (evenness.h)
// looks for uncovered surface and the relaxation (relax.h) for pockets. Internal to the
// library.
#pragma once

#include "meander/mesh.h"

#include <cstdint>
#include <span>
#include <vector>

namespace meander {

// Each face's area (its fan of triangles from its first corner), summed in face order.
// In parallel. O(n).
std::vector<double> cumulative_areas(const PolygonMesh& surface);

// `count` points of the surface, area-weighted, from `cumulative` (cumulative_areas, whose
// total must be positive): point s depends on seed and s alone, so the points are the
// same whatever the number of threads. O(count log n).
std::vector<Vec3> surface_samples(const PolygonMesh& surface, std::span<const double> cumulative, int32_t count,
                                  uint64_t seed);

} // namespace meander
