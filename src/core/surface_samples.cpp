#include "surface_samples.h"

#include "random.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace meander {

namespace {

double triangle_area(Vec3 a, Vec3 b, Vec3 c) {
  const double ux = double(b.x) - a.x, uy = double(b.y) - a.y, uz = double(b.z) - a.z;
  const double vx = double(c.x) - a.x, vy = double(c.y) - a.y, vz = double(c.z) - a.z;
  const double x = uy * vz - uz * vy, y = uz * vx - ux * vz, z = ux * vy - uy * vx;
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

// Surface sample s, area-weighted: its own random stream, so that any thread draws it the
// same. A face is picked by its share of the area, then a triangle of its fan by the
// rest of the same draw, then a point of the triangle uniformly.
Vec3 surface_sample(const PolygonMesh& surface, std::span<const double> cumulative, uint64_t seed, int32_t s) {
  Random random(seed ^ (uint64_t(s) * 0xd1b54a32d192ed03ULL));
  double u = random.unit() * cumulative.back();
  auto face = std::upper_bound(cumulative.begin(), cumulative.end(), u);
  // u rounded up to the total: the last face with area.
  if (face == cumulative.end()) face = std::lower_bound(cumulative.begin(), cumulative.end(), cumulative.back());
  const size_t f = size_t(face - cumulative.begin());
  if (f > 0) u -= cumulative[f - 1];
  const auto v = surface.face(int32_t(f));
  const Vec3 a = surface.positions[size_t(v[0])];
  size_t i = 1;
  for (; i + 2 < v.size(); ++i) {
    const double area = triangle_area(a, surface.positions[size_t(v[i])], surface.positions[size_t(v[i + 1])]);
    if (u < area) break;
    u -= area;
  }
  const Vec3 b = surface.positions[size_t(v[i])], c = surface.positions[size_t(v[i + 1])];
  const double r = std::sqrt(random.unit()), t = random.unit();
  const double wa = 1 - r, wb = r * (1 - t), wc = r * t;
  return {float(wa * a.x + wb * b.x + wc * c.x), float(wa * a.y + wb * b.y + wc * c.y),
          float(wa * a.z + wb * b.z + wc * c.z)};
}

} // namespace

// Each face's area (its fan of triangles from its first corner), summed in face order.
std::vector<double> cumulative_areas(const PolygonMesh& surface) {
  std::vector<double> area(size_t(surface.num_faces()));
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, surface.num_faces(), 4096),
                    [&](const tbb::blocked_range<int32_t>& r) {
                      for (int32_t f = r.begin(); f < r.end(); ++f) {
                        const auto v = surface.face(f);
                        double a = 0;
                        for (size_t i = 1; i + 1 < v.size(); ++i)
                          a += triangle_area(surface.positions[size_t(v[0])], surface.positions[size_t(v[i])],
                                             surface.positions[size_t(v[i + 1])]);
                        area[size_t(f)] = a;
                      }
                    });
  for (size_t f = 1; f < area.size(); ++f) area[f] += area[f - 1];
  return area;
}

std::vector<Vec3> surface_samples(const PolygonMesh& surface, std::span<const double> cumulative, int32_t count,
                                  uint64_t seed) {
  std::vector<Vec3> samples(size_t(std::max(count, 0)));
  tbb::parallel_for(tbb::blocked_range<int32_t>(0, count, 1024), [&](const tbb::blocked_range<int32_t>& range) {
    for (int32_t s = range.begin(); s < range.end(); ++s) samples[size_t(s)] = surface_sample(surface, cumulative, seed, s);
  });
  return samples;
}

} // namespace meander
