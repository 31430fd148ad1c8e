// 3-vectors as plain arrays, and the operations the stages do on them.
// Vec3d (double) is a point or extent in world units, shared by every stage;
// Vec3f (float) is what meshes store (core/surface_mesh.h).
//
// Every operation stays in its arguments' precision and evaluates in the
// order written here (dot: x, then + y, then + z), so a result is the same to
// the bit wherever it is computed. Mixing precisions does not compile: widen a
// float vector with toVec3d first (the meshes' geometry is done in double).
// No operation throws; normalised() of a zero vector gives its fallback.
#pragma once

#include <array>
#include <cmath>

namespace rockbake {

using Vec3d = std::array<double, 3>;
using Vec3f = std::array<float, 3>;

constexpr Vec3d toVec3d(const Vec3f& v) {
  return {double(v[0]), double(v[1]), double(v[2])};
}
constexpr Vec3f toVec3f(const Vec3d& v) {
  return {float(v[0]), float(v[1]), float(v[2])};
}

template <class T>
constexpr std::array<T, 3> add(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

template <class T>
constexpr std::array<T, 3> sub(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// a times s.
template <class T>
constexpr std::array<T, 3> scale(const std::array<T, 3>& a, T s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}

// a divided by s (not multiplied by 1 / s, which rounds differently).
template <class T>
constexpr std::array<T, 3> divide(const std::array<T, 3>& a, T s) {
  return {a[0] / s, a[1] / s, a[2] / s};
}

template <class T>
constexpr T dot(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Right-handed: cross({1, 0, 0}, {0, 1, 0}) = {0, 0, 1}.
template <class T>
constexpr std::array<T, 3> cross(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

template <class T>
constexpr T lengthSquared(const std::array<T, 3>& a) {
  return dot(a, a);
}

template <class T>
T length(const std::array<T, 3>& a) {
  return std::sqrt(dot(a, a));
}

template <class T>
constexpr T distanceSquared(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return lengthSquared(sub(a, b));
}

// a divided by its length; `fallback` when the length is not positive.
template <class T>
std::array<T, 3> normalised(const std::array<T, 3>& a, const std::array<T, 3>& fallback) {
  const T len = length(a);
  return len > 0 ? divide(a, len) : fallback;
}

}  // namespace rockbake
