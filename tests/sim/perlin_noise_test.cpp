// Improved Perlin noise (sim/durability.h): zero on the lattice, and at every lattice point
// its slope is one of the cube's 12 edge directions, picked as Perlin's reference picks them
// from 16 hash values (four of the edges twice as often as the rest); and the reference's
// values, to the bit.
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

// Values the reference implementation (Perlin's branches on the hash for the gradient) gave
// with this seed, to the bit: each point reads eight hashed gradients, so a table entry moved
// or changed shows.
TEST(PerlinNoise, GivesTheReferenceValuesToTheBit) {
  const PerlinNoise noise(20261128);
  const struct {
    double x, y, z, value;
  } reference[] = {
      {0.3, 0.7, 0.1, -0x1.6e0762dc6c70dp-3},      {1.25, -2.5, 3.75, -0x1.2c528p-4},
      {7.9, 3.1, -4.4, 0x1.687ba34a8cb6p-7},       {-0.6, 12.2, 5.5, -0x1.642b3970e5472p-2},
      {100.1, 200.2, 300.3, 0x1.96730111a19c4p-2}, {2.5, 2.5, 2.5, -0x1p-2},
  };
  for (const auto& r : reference) EXPECT_EQ(noise(r.x, r.y, r.z), r.value) << r.x << " " << r.y << " " << r.z;
}

}  // namespace
}  // namespace rockbake
