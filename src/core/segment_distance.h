// The closest distance between two segments: what the wire's self-intersection bound
// and the bridges' clearance measure. Internal to the library.
#pragma once

#include "meander/mesh.h"

#include <algorithm>
#include <cmath>

namespace meander {

// Closest distance between segments [p0,p1] and [q0,q1] (Ericson, Real-Time Collision
// Detection, 5.1.9), in double.
inline double segment_distance(Vec3 p0, Vec3 p1, Vec3 q0, Vec3 q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return norm(r);
  if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  const double x = r.x + d1.x * s - d2.x * t, y = r.y + d1.y * s - d2.y * t, z = r.z + d1.z * s - d2.z * t;
  return std::sqrt(x * x + y * y + z * z);
}

} // namespace meander
