// Small vector and topology helpers of the texture stage. To be replaced by the mesh
// kernel's vec3 operations and edge table (baker/core) once they land.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rockbake::texture_detail {

using V3 = std::array<double, 3>;

inline V3 toV3(const std::array<float, 3>& a) {
  return {a[0], a[1], a[2]};
}
inline V3 add(const V3& a, const V3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline V3 sub(const V3& a, const V3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline V3 scale(const V3& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
inline double dot(const V3& a, const V3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double length(const V3& a) {
  return std::sqrt(dot(a, a));
}
// a / |a|, or zero for a zero vector.
inline V3 normalized(const V3& a) {
  const double l = length(a);
  return l > 0 ? scale(a, 1.0 / l) : V3{0, 0, 0};
}

constexpr std::uint32_t kNoTriangle = 0xffffffffu;

// For each triangle t and edge k (corner k to corner k + 1), the triangle across it, or
// kNoTriangle where the edge is open, shared by more than two triangles, or shared by two
// that traverse it the same way (facing opposite sides). Deterministic.
std::vector<std::array<std::uint32_t, 3>> triangleNeighbours(
    const std::vector<std::array<std::uint32_t, 3>>& triangles);

}  // namespace rockbake::texture_detail
