// The mesh kernel's vector operations and triangle geometry (core/vec3.h,
// core/triangle_geometry.h; docs/mesh-kernel.md): known values, and the
// evaluation order each one promises, to the bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/hash.h"
#include "core/triangle_geometry.h"
#include "core/vec3.h"

namespace rockbake {
namespace {

// Reproducible values spread over many magnitudes, so a changed order of
// operations shows up as a changed last bit.
double value(std::uint64_t i) {
  const std::uint64_t h = mix64(i);
  return (double(h >> 11) / double(1ull << 53) - 0.5) * std::ldexp(1.0, int(h % 40) - 20);
}
Vec3d randomVec3d(std::uint64_t i) {
  return {value(3 * i), value(3 * i + 1), value(3 * i + 2)};
}
Vec3f randomVec3f(std::uint64_t i) {
  return toVec3f(randomVec3d(i));
}

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(Vec3, KnownValues) {
  const Vec3d x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  EXPECT_EQ(cross(x, y), z);  // right-handed
  EXPECT_EQ(cross(y, z), x);
  EXPECT_EQ(cross(z, x), y);
  EXPECT_EQ(cross(y, x), (Vec3d{0, 0, -1}));
  EXPECT_EQ(add(Vec3d{1, 2, 3}, Vec3d{4, 5, 6}), (Vec3d{5, 7, 9}));
  EXPECT_EQ(sub(Vec3d{1, 2, 3}, Vec3d{4, 6, 8}), (Vec3d{-3, -4, -5}));
  EXPECT_EQ(scale(Vec3d{1, 2, 3}, 2.0), (Vec3d{2, 4, 6}));
  EXPECT_EQ(divide(Vec3d{2, 4, 6}, 2.0), (Vec3d{1, 2, 3}));
  EXPECT_EQ(dot(Vec3d{1, 2, 3}, Vec3d{4, 5, 6}), 32.0);
  EXPECT_EQ(length(Vec3d{3, 4, 12}), 13.0);
  EXPECT_EQ(lengthSquared(Vec3f{1, 2, 2}), 9.0f);
  EXPECT_EQ(distanceSquared(Vec3f{1, 1, 1}, Vec3f{2, 3, 3}), 9.0f);
  EXPECT_EQ(normalised(Vec3d{0, 3, 4}, x), (Vec3d{0, 0.6, 0.8}));
  EXPECT_EQ(normalised(Vec3d{0, 0, 0}, z), z);  // the fallback
  EXPECT_EQ(toVec3f(Vec3d{0.1, 0.2, 0.3}), (Vec3f{0.1f, 0.2f, 0.3f}));
  EXPECT_EQ(toVec3d(Vec3f{0.5f, 0.25f, 2.0f}), (Vec3d{0.5, 0.25, 2.0}));
}

// Each operation is exactly the expression it replaced, written out here.
TEST(Vec3, EvaluationOrderIsTheWrittenOne) {
  for (std::uint64_t i = 0; i < 2000; ++i) {
    const Vec3d a = randomVec3d(2 * i), b = randomVec3d(2 * i + 1);
    const double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    ASSERT_TRUE(sameBits(dot(a, b), d)) << i;
    const Vec3d c = cross(a, b);
    ASSERT_TRUE(sameBits(c[0], a[1] * b[2] - a[2] * b[1])) << i;
    ASSERT_TRUE(sameBits(c[1], a[2] * b[0] - a[0] * b[2])) << i;
    ASSERT_TRUE(sameBits(c[2], a[0] * b[1] - a[1] * b[0])) << i;
    ASSERT_TRUE(sameBits(length(a), std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]))) << i;
    const double len = length(a);
    const Vec3d n = normalised(a, Vec3d{0, 0, 1});
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(sameBits(n[k], a[k] / len)) << i;  // divided, not times 1 / len
    const Vec3f fa = randomVec3f(2 * i), fb = randomVec3f(2 * i + 1);
    const float dx = fa[0] - fb[0], dy = fa[1] - fb[1], dz = fa[2] - fb[2];
    ASSERT_EQ(distanceSquared(fa, fb), dx * dx + dy * dy + dz * dz) << i;  // in float throughout
  }
}

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
