// One triangle's geometry (geometry/triangle_geometry.h; docs/mesh-kernel.md):
// known values, the cross product in double to the bit, and zero area relative
// to the triangle's size. The vector operations under it: tests/core/vec3_test.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "core/vec3.h"
#include "geometry/triangle_geometry.h"
#include "test_support.h"

namespace rockbake {
namespace {

using test::randomVec3f;
using test::sameBits;

TEST(TriangleGeometry, NormalAreaAndVolumeOfKnownTriangles) {
  const Vec3f a{0, 0, 0}, b{2, 0, 0}, c{0, 3, 0};
  EXPECT_EQ(triangleNormal(a, b, c), (Vec3d{0, 0, 6}));  // counter-clockwise from +z: up, twice the area
  EXPECT_EQ(triangleNormal(a, c, b), (Vec3d{0, 0, -6}));
  EXPECT_EQ(triangleArea(a, b, c), 3.0);
  // A unit cube's corner tetrahedron, and the cube from its twelve triangles.
  EXPECT_DOUBLE_EQ(tetVolume(Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1}), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(tetVolume(Vec3d{1, 0, 0}, Vec3d{0, 0, 1}, Vec3d{0, 1, 0}), -1.0 / 6.0);
  EXPECT_DOUBLE_EQ(tetVolume(Vec3f{1, 0, 0}, Vec3f{0, 1, 0}, Vec3f{0, 0, 1}), 1.0 / 6.0);
}

TEST(TriangleGeometry, NormalAndAreaAreTheCrossProductInDouble) {
  for (std::uint64_t i = 0; i < 2000; ++i) {
    const Vec3f a = randomVec3f(3 * i), b = randomVec3f(3 * i + 1), c = randomVec3f(3 * i + 2);
    const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double w[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const Vec3d normal = triangleNormal(a, b, c);
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(sameBits(normal[k], n[k])) << i;
    ASSERT_TRUE(sameBits(triangleArea(a, b, c), 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]))) << i;
  }
}

TEST(TriangleGeometry, ZeroAreaIsRelativeToTheTrianglesSize) {
  // A cap: the apex 1e-7 off the long edge's line is zero area; 1e-5 off is not.
  for (float scale : {1e-3f, 1.0f, 1e3f}) {
    const Vec3f a{0, 0, 0}, b{scale, 0, 0};
    EXPECT_TRUE(isZeroArea(a, b, Vec3f{0.5f * scale, 1e-7f * scale, 0})) << scale;
    EXPECT_FALSE(isZeroArea(a, b, Vec3f{0.5f * scale, 1e-5f * scale, 0})) << scale;
  }
  // Repeated corners and a needle.
  EXPECT_TRUE(isZeroArea(Vec3f{1, 2, 3}, Vec3f{1, 2, 3}, Vec3f{4, 5, 6}));
  EXPECT_TRUE(isZeroArea(Vec3f{0, 0, 0}, Vec3f{1, 1, 1}, Vec3f{2, 2, 2}));
  EXPECT_FALSE(isZeroArea(Vec3f{0, 0, 0}, Vec3f{1, 0, 0}, Vec3f{0, 1, 0}));
}

}  // namespace
}  // namespace rockbake
