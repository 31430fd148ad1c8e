// The signed distance the rind and shape variation read (sim/distance_field.h):
// an exact Euclidean transform, checked against the brute-force nearest centre.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "sim/distance_field.h"

namespace rockbake {
namespace {

// Blobs of cells (a few random balls), so both kinds form runs and holes.
std::vector<std::uint8_t> blobs(const GridLayout& g, std::mt19937& random) {
  std::vector<std::uint8_t> inside(g.cellCount(), 0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int b = 0; b < 5; ++b) {
    const double cx = u(random) * g.nx, cy = u(random) * g.ny, cz = u(random) * g.nz;
    const double r = 1.0 + u(random) * 4.0;
    const bool hole = b == 4;
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x)
          if (std::hypot(x + 0.5 - cx, y + 0.5 - cy, z + 0.5 - cz) < r) inside[g.index(x, y, z)] = hole ? 0 : 1;
  }
  return inside;
}

// The distance from a cell's centre to the nearest centre of the other kind,
// the outside continuing beyond the sides and top (and the bottom without ground).
double bruteForce(const std::vector<std::uint8_t>& inside, const GridLayout& g, int x, int y, int z) {
  const bool in = inside[g.index(x, y, z)] != 0;
  double best = std::numeric_limits<double>::infinity();
  if (in) {
    best = std::min({x + 1, g.nx - x, y + 1, g.ny - y, g.nz - z}) * 1.0;
    if (!g.ground) best = std::min(best, z + 1.0);
  }
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        if ((inside[g.index(i, j, k)] != 0) != in) best = std::min(best, std::hypot(i - x, j - y, k - z));
  return best;
}

TEST(DistanceField, EqualsTheNearestCentreOfTheOtherKindOnRandomGrids) {
  std::mt19937 random(7);
  for (const bool ground : {true, false})
    // 3 voxels: clamped; 40: the whole grid, two bytes a cell; 200: four bytes a cell.
    for (const double reach : {3.0, 40.0, 200.0})
      for (int trial = 0; trial < 3; ++trial) {
        GridLayout g;
        g.nx = 9 + trial * 3;
        g.ny = 7 + trial;
        g.nz = 11 - trial;
        g.h = 0.5;
        g.ground = ground;
        const auto inside = blobs(g, random);
        const SignedDistanceField field = signedDistance(inside, g, reach * g.h);
        for (int z = 0; z < g.nz; ++z)
          for (int y = 0; y < g.ny; ++y)
            for (int x = 0; x < g.nx; ++x) {
              const std::size_t i = g.index(x, y, z);
              const double centre = bruteForce(inside, g, x, y, z);
              double expected = std::min((centre - 0.5) * g.h, reach * g.h);
              if (inside[i]) expected = -expected;
              ASSERT_NEAR(field[i], expected, 1e-9)
                  << "cell (" << x << ", " << y << ", " << z << "), ground " << ground << ", reach " << reach;
            }
      }
}

TEST(DistanceField, IsAPlaneAwayFromAFlatBoundary) {
  // The lower half of a column of cells 5 × 5 wide: along its axis, the
  // boundary lies midway between the top rock layer and the air above it (the
  // sides are 3 cells away; the ground adds no boundary below).
  GridLayout g;
  g.nx = g.ny = 5;
  g.nz = 40;
  g.h = 0.25;
  std::vector<std::uint8_t> inside(g.cellCount(), 0);
  for (int z = 0; z < 20; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) inside[g.index(x, y, z)] = 1;
  const SignedDistanceField field = signedDistance(inside, g, 10.0);
  EXPECT_DOUBLE_EQ(field[g.index(2, 2, 19)], -0.5 * g.h);
  EXPECT_DOUBLE_EQ(field[g.index(2, 2, 20)], 0.5 * g.h);
  EXPECT_DOUBLE_EQ(field[g.index(2, 2, 30)], 10.5 * g.h);
  EXPECT_DOUBLE_EQ(field[g.index(2, 2, 18)], -1.5 * g.h);
}

}  // namespace
}  // namespace rockbake
