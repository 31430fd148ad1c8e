// One triangle's geometry, the single definition every stage uses: its normal
// and area, whether it has zero area, and the signed volume of the tetrahedron
// it spans with the origin. Corners are float (the meshes' Vec3f) or double
// (a blockout's TriangleMesh); all arithmetic is double, in the order written
// here, so a check gives the same answer wherever it is made. Nothing throws.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "core/vec3.h"

namespace rockbake {

// (b − a) × (c − a): outward for a counter-clockwise triangle seen from
// outside, of length twice the area. Not normalised.
inline Vec3d triangleNormal(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  const Vec3d da = toVec3d(a);
  return cross(sub(toVec3d(b), da), sub(toVec3d(c), da));
}

inline double triangleArea(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  return 0.5 * length(triangleNormal(a, b, c));
}

// Zero area relative to the triangle's own size: twice its area at most 2e-6
// of its longest edge squared (a sliver or a cap far thinner than any the
// meshes are meant to hold, at any scale).
inline bool isZeroArea(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  const Vec3d pa = toVec3d(a), pb = toVec3d(b), pc = toVec3d(c);
  const Vec3d e0 = sub(pb, pa), e1 = sub(pc, pa), e2 = sub(pc, pb);
  return length(cross(e0, e1)) <= 2e-6 * std::max({lengthSquared(e0), lengthSquared(e1), lengthSquared(e2)});
}

// Signed volume of the tetrahedron (origin, p, q, r): p · (q × r) / 6, in
// cubed position units; summed over a closed mesh's triangles, the volume it
// encloses (positive when they face outwards).
template <class T>
double tetVolume(const std::array<T, 3>& p, const std::array<T, 3>& q, const std::array<T, 3>& r) {
  return (double(p[0]) * (double(q[1]) * r[2] - double(q[2]) * r[1]) -
          double(p[1]) * (double(q[0]) * r[2] - double(q[2]) * r[0]) +
          double(p[2]) * (double(q[0]) * r[1] - double(q[1]) * r[0])) /
         6.0;
}

}  // namespace rockbake
