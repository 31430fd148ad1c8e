// Small vector operations on Vec3d for the collision stage. To be replaced by
// the core's vec3 operations once the mesh kernel provides them.
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace rockbake::collision_detail {

inline Vec3d operator+(const Vec3d& a, const Vec3d& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3d operator-(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3d operator*(double s, const Vec3d& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double length(const Vec3d& a) {
  return std::sqrt(dot(a, a));
}

}  // namespace rockbake::collision_detail
