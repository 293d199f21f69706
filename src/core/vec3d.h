// Vec3 in double precision, for the geometry whose results must not depend on float
// rounding: printability's exact signs, the renderer's camera and shading, and the
// subdivision's deep levels. Every Vec3 converts exactly. Internal to the library (the
// public types stay float, see mesh.h).
#pragma once

#include "meander/mesh.h"

namespace meander {

struct Vec3d {
  double x = 0, y = 0, z = 0;

  friend Vec3d operator+(Vec3d a, Vec3d b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend Vec3d operator*(Vec3d a, double s) { return {a.x * s, a.y * s, a.z * s}; }
};

inline Vec3d to_double(Vec3 p) { return {p.x, p.y, p.z}; }
inline Vec3 to_float(Vec3d p) { return {float(p.x), float(p.y), float(p.z)}; }

inline double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3d cross(Vec3d a, Vec3d b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

} // namespace meander
