// The collision stage's pieces (docs/collision.md): Qhull's hulls and
// half-space intersections, the parts and the vertex cap, on shapes whose
// answers are known by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "collision/point_hull.h"
#include "collision/reduce_hull.h"
#include "collision/voxel_parts.h"

namespace rockbake {
namespace {

std::vector<Vec3d> cubeCorners(double lo, double hi) {
  std::vector<Vec3d> c;
  for (double x : {lo, hi})
    for (double y : {lo, hi})
      for (double z : {lo, hi}) c.push_back({x, y, z});
  return c;
}

TEST(PointHull, CubeHasEightVerticesSixPlanesAndItsVolume) {
  std::vector<Vec3d> points = cubeCorners(0, 2);
  points.push_back({1, 1, 1});  // inside
  points.push_back({1, 0, 1});  // on a face
  const PointHull hull = hullOfPoints(points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.planes.size(), 6u);
  EXPECT_NEAR(hull.volume, 8.0, 1e-12);
  EXPECT_TRUE(std::is_sorted(hull.vertices.begin(), hull.vertices.end()));
  for (const HullPlane& p : hull.planes)
    for (const Vec3d& v : hull.vertices)
      EXPECT_LE(p.normal[0] * v[0] + p.normal[1] * v[1] + p.normal[2] * v[2], p.offset + 1e-12);
}

TEST(PointHull, TriangulatedCubeIsClosedAndOutward) {
  const TriangulatedHull t = triangulateHull(cubeCorners(-1, 1));
  ASSERT_EQ(t.vertices.size(), 8u);
  ASSERT_EQ(t.triangles.size(), 12u);
  double volume = 0;
  for (const auto& tri : t.triangles) {
    const Vec3d &a = t.vertices[tri[0]], &b = t.vertices[tri[1]], &c = t.vertices[tri[2]];
    volume +=
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) /
        6.0;
  }
  EXPECT_NEAR(volume, 8.0, 1e-12);  // positive: counter-clockwise seen from outside
}

TEST(PointHull, HalfSpacesOfAnOctahedron) {
  std::vector<HullPlane> planes;
  const double s = 1.0 / std::sqrt(3.0);
  for (double x : {-s, s})
    for (double y : {-s, s})
      for (double z : {-s, s}) planes.push_back({{x, y, z}, s});  // |x| + |y| + |z| <= 1
  const Polytope octahedron = intersectHalfSpaces(planes, {0.1, -0.2, 0.05});
  std::vector<Vec3d> v = octahedron.vertices;
  ASSERT_EQ(v.size(), 6u);
  for (Vec3d& p : v)
    for (double& c : p) c = std::round(c * 1e9) / 1e9 + 0.0;  // -0 → 0, for the sort
  std::sort(v.begin(), v.end());
  const std::vector<Vec3d> expected = {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  for (std::size_t i = 0; i < 6; ++i)
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(v[i][a], expected[i][a], 1e-12) << i;
}

// Voxel corners of a ball of radius 6: many hull vertices.
std::vector<Vec3d> ballCorners() {
  std::vector<Vec3d> points;
  for (int x = -6; x < 6; ++x)
    for (int y = -6; y < 6; ++y)
      for (int z = -6; z < 6; ++z)
        if ((x + 0.5) * (x + 0.5) + (y + 0.5) * (y + 0.5) + (z + 0.5) * (z + 0.5) <= 36)
          for (int dx = 0; dx < 2; ++dx)
            for (int dy = 0; dy < 2; ++dy)
              for (int dz = 0; dz < 2; ++dz) points.push_back({double(x + dx), double(y + dy), double(z + dz)});
  return points;
}

TEST(ReduceHull, CapsTheVerticesAndKeepsTheHullInside) {
  const PointHull ball = hullOfPoints(ballCorners());
  ASSERT_GT(ball.vertices.size(), 64u);
  for (const int cap : {8, 16, 64}) {
    const CappedHull reduced = reduceHull(ball, cap);
    const PointHull polytope = hullOfPoints(reduced.vertices);
    EXPECT_LE(polytope.vertices.size(), std::size_t(cap));
    EXPECT_GE(polytope.volume, ball.volume);
    for (const HullPlane& p : polytope.planes)
      for (const Vec3d& v : ball.vertices)
        ASSERT_LE(p.normal[0] * v[0] + p.normal[1] * v[1] + p.normal[2] * v[2], p.offset + 1e-9) << cap;
    // More vertices, less air.
    if (cap == 8) {
      EXPECT_NEAR(polytope.volume, 12.0 * 12.0 * 12.0, 1e-9);  // the bounding box
    }
    if (cap == 64) {
      EXPECT_LT(polytope.volume, 1.25 * ball.volume);
    }
    std::printf("cap %d: %zu vertices, volume %.1f (hull %.1f)\n", cap, polytope.vertices.size(), polytope.volume,
                ball.volume);
  }
  EXPECT_EQ(reduceHull(ball, 255).vertices, ball.vertices);  // within the cap: as it is
}

}  // namespace
}  // namespace rockbake
