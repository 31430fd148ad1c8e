// The mesh kernel's vector operations (core/vec3.h; docs/mesh-kernel.md): known
// values, and the evaluation order each one promises, to the bit. Triangle
// geometry built on them: tests/geometry/triangle_geometry_test.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "core/vec3.h"
#include "test_support.h"

namespace rockbake {
namespace {

using test::randomVec3d;
using test::randomVec3f;
using test::sameBits;

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

}  // namespace
}  // namespace rockbake
