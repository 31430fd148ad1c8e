// Shared by the collision tests: the weathered rock they hull, and the checks
// every hull must pass.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "collision/collision_hulls.h"
#include "inputs/resolve_shape.h"
#include "preset/load_preset.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake::test {

// The weathered default preset at a test resolution, colluvium and all.
inline const VoxelRock& weatheredGoblin() {
  static const VoxelRock rock = [] {
    // The blockout as the preset gives it (its family aside): the rock bench/README.md's hull figures are of.
    Preset p = loadPreset(sourceDir() / "presets" / "goblin.yaml", {{}, std::nullopt, 40});
    p.family.reset();
    return weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
  }();
  return rock;
}

// Every edge used once each way; every vertex on the inner side of every
// face (so the hull is convex and its faces point out); the volume its
// triangles enclose is positive and the one it reports.
// `tolerance`: how far (world units) a vertex may stray outside a face's plane;
// `volume_tolerance`: relative.
inline void expectClosedConvexOutward(const ConvexHull& hull, double tolerance, const std::string& what,
                                      double volume_tolerance = 1e-9) {
  ASSERT_GE(hull.positions.size(), 4u) << what;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : hull.triangles)
    for (int i = 0; i < 3; ++i) ++edges[{t[i], t[(i + 1) % 3]}];
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1) << what << ": edge " << e.first << "-" << e.second << " used " << n << " times one way";
    EXPECT_EQ(edges.count({e.second, e.first}), 1u)
        << what << ": edge " << e.first << "-" << e.second << " has no twin";
  }
  // Euler: a closed sphere-like surface.
  EXPECT_EQ(hull.positions.size() + hull.triangles.size() - edges.size() / 2, 2u) << what;
  double volume = 0;
  for (const auto& t : hull.triangles) {
    const Vec3d &a = hull.positions[t[0]], &b = hull.positions[t[1]], &c = hull.positions[t[2]];
    const Vec3d n = cross(sub(b, a), sub(c, a));
    const double area2 = std::sqrt(dot(n, n));
    ASSERT_GT(area2, 0) << what << ": a zero-area face";
    for (const Vec3d& v : hull.positions)
      ASSERT_LE(dot(n, sub(v, a)) / area2, tolerance) << what << ": a vertex outside a face's plane";
    volume += dot(a, cross(b, c)) / 6;
  }
  EXPECT_GT(volume, 0) << what;
  EXPECT_NEAR(volume, hull.volume, volume_tolerance * std::abs(volume)) << what;
}

}  // namespace rockbake::test
