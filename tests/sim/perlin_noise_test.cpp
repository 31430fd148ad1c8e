// Improved Perlin noise (sim/durability.h): zero on the lattice, and at every lattice point
// its slope is one of the cube's 12 edge directions, picked as Perlin's reference picks them
// from 16 hash values (four of the edges twice as often as the rest).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "sim/durability.h"

namespace rockbake {
namespace {

TEST(PerlinNoise, SlopesAtTheLatticeAreTheCubesEdgesInTheReferencesProportions) {
  const PerlinNoise noise(20261128);
  std::map<std::array<int, 3>, int> count;
  constexpr double kStep = 1e-7;  // the other corners' terms go as the fade, 10 · step³
  int points = 0;
  for (int x = 0; x < 16; ++x)
    for (int y = 0; y < 16; ++y)
      for (int z = 0; z < 16; ++z) {
        ASSERT_EQ(noise(x, y, z), 0.0);
        std::array<int, 3> slope{};
        for (int k = 0; k < 3; ++k) {
          const double s = noise(x + (k == 0) * kStep, y + (k == 1) * kStep, z + (k == 2) * kStep) / kStep;
          slope[std::size_t(k)] = int(std::lround(s));
          ASSERT_NEAR(s, slope[std::size_t(k)], 1e-6);
        }
        ASSERT_EQ(std::abs(slope[0]) + std::abs(slope[1]) + std::abs(slope[2]), 2) << x << " " << y << " " << z;
        ++count[slope];
        ++points;
      }
  ASSERT_EQ(count.size(), 12u);  // every edge of the cube, nothing else
  // The reference's hashes 12 … 15 repeat (1, 1, 0), (0, −1, 1), (−1, 1, 0) and (0, −1, −1).
  const std::array<std::array<int, 3>, 4> twice{{{1, 1, 0}, {0, -1, 1}, {-1, 1, 0}, {0, -1, -1}}};
  for (const auto& [slope, n] : count) {
    const bool doubled = std::find(twice.begin(), twice.end(), slope) != twice.end();
    const double expected = points * (doubled ? 2.0 : 1.0) / 16.0;
    EXPECT_NEAR(n, expected, 0.3 * expected) << slope[0] << " " << slope[1] << " " << slope[2];
  }
}

}  // namespace
}  // namespace rockbake
