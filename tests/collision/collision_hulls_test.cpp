// Collision hulls from the voxels (docs/collision.md): analytic blocks whose
// decomposition is known by hand, and a weathered rock with its colluvium,
// checked the way an engine relies on them: convex, closed, outward, every
// voxel inside, little air, within the caps, the same at any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

#include <tbb/global_control.h>

#include "collision/collision_hulls.h"
#include "collision/hull_checks.h"
#include "collision/hull_coverage.h"
#include "inputs/resolve_shape.h"
#include "preset/load_preset.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

using test::expectClosedConvexOutward;
using test::weatheredGoblin;

// An all-air grid on the ground, h = 0.25, with `solid` deciding which cells are rock.
VoxelRock blockRock(int nx, int ny, int nz, const std::function<bool(int, int, int)>& solid) {
  VoxelRock rock;
  GridLayout& g = rock.layout;
  g.nx = nx, g.ny = ny, g.nz = nz;
  g.margin = 2;
  g.h = 0.25;
  g.origin = {-1.0, -2.0, 0.0};
  rock.material.assign(g.cellCount(), Material::Air);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        if (solid(x, y, z)) rock.material[g.index(x, y, z)] = Material::Rock;
  resetRockValues(rock);
  return rock;
}

// Every voxel of `material`, all eight corners, inside one hull (the hull of
// the piece that holds it): the union covers the voxels, not just their centres.
void expectEveryVoxelInside(const VoxelRock& rock, Material material, const std::vector<ConvexHull>& hulls) {
  struct Plane {
    Vec3d n;
    double d;
  };
  std::vector<std::vector<Plane>> planes;
  for (const ConvexHull& hull : hulls) {
    planes.emplace_back();
    for (const auto& t : hull.triangles) {
      const Vec3d n =
          cross(sub(hull.positions[t[1]], hull.positions[t[0]]), sub(hull.positions[t[2]], hull.positions[t[0]]));
      const double len = std::sqrt(dot(n, n));
      const Vec3d u{n[0] / len, n[1] / len, n[2] / len};
      planes.back().push_back({u, dot(u, hull.positions[t[0]])});
    }
  }
  const GridLayout& g = rock.layout;
  const double eps = 1e-9 * g.h;
  std::size_t outside = 0;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        if (rock.material[g.index(x, y, z)] != material) continue;
        const bool held = std::any_of(planes.begin(), planes.end(), [&](const std::vector<Plane>& hull) {
          for (int c = 0; c < 8; ++c) {
            const Vec3d p{g.origin[0] + (x + (c & 1)) * g.h, g.origin[1] + (y + (c >> 1 & 1)) * g.h,
                          g.origin[2] + (z + (c >> 2)) * g.h};
            for (const Plane& f : hull)
              if (dot(f.n, p) > f.d + eps) return false;
          }
          return true;
        });
        outside += !held;
      }
  EXPECT_EQ(outside, 0u) << "voxels not inside any one hull";
}

TEST(CollisionHulls, BoxIsOneHullOfEightVertices) {
  const VoxelRock rock =
      blockRock(16, 12, 10, [](int x, int y, int z) { return x >= 2 && x < 12 && y >= 3 && y < 9 && z < 4; });
  const std::vector<ConvexHull> hulls = hullVoxels(rock, Material::Rock, {});
  ASSERT_EQ(hulls.size(), 1u);
  const ConvexHull& box = hulls[0];
  EXPECT_EQ(box.positions.size(), 8u);
  EXPECT_EQ(box.triangles.size(), 12u);
  EXPECT_EQ(box.voxels, 10u * 6u * 4u);
  EXPECT_NEAR(box.volume, 10 * 6 * 4 * 0.25 * 0.25 * 0.25, 1e-12);
  // Its corners are the voxels' outer corners, in world units.
  for (const Vec3d& p : box.positions) {
    EXPECT_TRUE(p[0] == -1.0 + 2 * 0.25 || p[0] == -1.0 + 12 * 0.25) << p[0];
    EXPECT_TRUE(p[1] == -2.0 + 3 * 0.25 || p[1] == -2.0 + 9 * 0.25) << p[1];
    EXPECT_TRUE(p[2] == 0.0 || p[2] == 4 * 0.25) << p[2];
  }
  expectClosedConvexOutward(box, 1e-12, "box");
  const HullCoverage c = measureCoverage(rock, Material::Rock, hulls);
  EXPECT_EQ(c.voxels_inside, c.voxels);
  EXPECT_EQ(c.air_inside, 0u);
}

TEST(CollisionHulls, LShapedBlockIsTwoHullsThatClaimAlmostNoAir) {
  // Two 13-voxel-thick walls, 40 long, meeting at a right angle, 20 high: the
  // inside corner falls inside a block of parts, not on a block's side.
  const auto wall = [](int x, int y, int z) { return z < 20 && x < 40 && y < 40 && (x < 13 || y < 13); };
  const VoxelRock rock = blockRock(44, 44, 24, wall);
  const std::vector<ConvexHull> hulls = hullVoxels(rock, Material::Rock, {});
  ASSERT_EQ(hulls.size(), 2u);
  for (const ConvexHull& h : hulls) expectClosedConvexOutward(h, 1e-12, "L");
  const std::size_t voxels = 40 * 13 * 20 + 27 * 13 * 20;
  EXPECT_EQ(hulls[0].voxels + hulls[1].voxels, voxels);
  const HullCoverage c = measureCoverage(rock, Material::Rock, hulls);
  EXPECT_EQ(c.voxels_inside, voxels);
  EXPECT_LE(c.airPerVoxel(), 0.02);
  expectEveryVoxelInside(rock, Material::Rock, hulls);
  // One hull fills in the missing quadrant: 27 × 27 × 20 cells, half of them and more.
  const std::vector<ConvexHull> one = hullVoxels(rock, Material::Rock, {.max_hulls = 1});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_GT(measureCoverage(rock, Material::Rock, one).air_inside, 27u * 27u * 20u / 2u);
}

TEST(CollisionHulls, WeatheredRockAndColluvium) {
  const VoxelRock& rock = weatheredGoblin();
  const CollisionParams params{.colluvium = true};
  const CollisionHulls hulls = buildCollisionHulls(rock, params);
  for (const auto& [material, list] :
       {std::pair{Material::Rock, &hulls.rock}, std::pair{Material::Colluvium, &hulls.colluvium}}) {
    const std::string what = material == Material::Rock ? "rock" : "colluvium";
    ASSERT_FALSE(list->empty()) << what;
    EXPECT_LE(list->size(), std::size_t(params.max_hulls)) << what;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const ConvexHull& h = (*list)[i];
      EXPECT_LE(h.positions.size(), std::size_t(params.max_vertices)) << what;
      expectClosedConvexOutward(h, 1e-9 * rock.layout.h, what + " hull " + std::to_string(i));
      if (i > 0) {
        EXPECT_GE((*list)[i - 1].volume, h.volume) << "largest first";
      }
    }
    const HullCoverage c = measureCoverage(rock, material, *list);
    EXPECT_GE(c.coverage(), 0.98) << what;
    EXPECT_EQ(c.voxels_inside, c.voxels) << what << ": every hull holds its piece, so every voxel is inside";
    expectEveryVoxelInside(rock, material, *list);
    std::printf("%s: %zu voxels, %zu hulls, %.3f air voxels per voxel\n", what.c_str(), c.voxels, list->size(),
                c.airPerVoxel());
  }
  // The rock claims little air (at this coarse resolution its surface is rougher);
  // one hull of it claims several times more.
  const HullCoverage rockCover = measureCoverage(rock, Material::Rock, hulls.rock);
  const std::vector<ConvexHull> one = hullVoxels(rock, Material::Rock, {.max_hulls = 1, .max_vertices = 255});
  const double single = measureCoverage(rock, Material::Rock, one).airPerVoxel();
  std::printf("one hull: %.3f air voxels per rock voxel\n", single);
  EXPECT_LE(rockCover.airPerVoxel(), 0.25);  // 0.2 on goblin at its own resolution (bench/README.md)
  EXPECT_LT(rockCover.airPerVoxel(), 0.3 * single);
}

TEST(CollisionHulls, TightCapsHold) {
  const VoxelRock& rock = weatheredGoblin();
  for (const CollisionParams params :
       {CollisionParams{.max_hulls = 1, .max_vertices = 8}, CollisionParams{.max_hulls = 4, .max_vertices = 12}}) {
    const std::vector<ConvexHull> hulls = hullVoxels(rock, Material::Rock, params);
    ASSERT_FALSE(hulls.empty());
    EXPECT_LE(hulls.size(), std::size_t(params.max_hulls));
    for (const ConvexHull& h : hulls) {
      EXPECT_LE(h.positions.size(), std::size_t(params.max_vertices));
      expectClosedConvexOutward(h, 1e-9 * rock.layout.h, "capped");
    }
    expectEveryVoxelInside(rock, Material::Rock, hulls);
  }
}

TEST(CollisionHulls, LooseVoxelsEverywhere) {
  // Many separate specks: the caps and the coverage still hold.
  const VoxelRock rock = test::randomRock(24, 20, 16, 7, 0.15);
  const std::vector<ConvexHull> hulls = hullVoxels(rock, Material::Rock, {.max_hulls = 6, .max_vertices = 16});
  ASSERT_FALSE(hulls.empty());
  EXPECT_LE(hulls.size(), 6u);
  for (const ConvexHull& h : hulls) {
    EXPECT_LE(h.positions.size(), 16u);
    expectClosedConvexOutward(h, 1e-9 * rock.layout.h, "specks");
  }
  expectEveryVoxelInside(rock, Material::Rock, hulls);
}

TEST(CollisionHulls, SameHullsAtAnyThreadCount) {
  const VoxelRock& rock = weatheredGoblin();
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    return buildCollisionHulls(rock, {.colluvium = true});
  };
  const CollisionHulls one = run(1), two = run(2);
  for (const auto& [a, b] : {std::pair{&one.rock, &two.rock}, std::pair{&one.colluvium, &two.colluvium}}) {
    ASSERT_EQ(a->size(), b->size());
    for (std::size_t i = 0; i < a->size(); ++i) {
      EXPECT_EQ((*a)[i].positions, (*b)[i].positions);  // bit for bit
      EXPECT_EQ((*a)[i].triangles, (*b)[i].triangles);
      EXPECT_EQ((*a)[i].volume, (*b)[i].volume);
    }
  }
}

TEST(CollisionHulls, NothingToHullAndBadParameters) {
  const VoxelRock rock = blockRock(8, 8, 8, [](int x, int y, int z) { return x == 3 && y == 3 && z < 2; });
  const CollisionHulls hulls = buildCollisionHulls(rock, {});
  EXPECT_EQ(hulls.rock.size(), 1u);
  EXPECT_TRUE(hulls.colluvium.empty());                            // not asked for
  EXPECT_TRUE(hullVoxels(rock, Material::Colluvium, {}).empty());  // none there
  EXPECT_THROW(hullVoxels(rock, Material::Rock, {.max_hulls = 0}), std::invalid_argument);
  EXPECT_THROW(hullVoxels(rock, Material::Rock, {.max_hulls = 101}), std::invalid_argument);
  EXPECT_THROW(hullVoxels(rock, Material::Rock, {.max_vertices = 7}), std::invalid_argument);
  EXPECT_THROW(hullVoxels(rock, Material::Rock, {.max_vertices = 256}), std::invalid_argument);
}

}  // namespace
}  // namespace rockbake
