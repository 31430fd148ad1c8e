// Rockfall (docs/model.md §6).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "debris_fixtures.h"
#include "sim/rockfall.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

using Cell = std::uint32_t;
using test::at;
using test::emptyRock;
using test::fill;
using test::floatingCount;
using test::neckPreset;
using test::nothingFloats;
using test::solidCount;

TEST(Rockfall, AFloatingBlockFallsAndRestsOnTheGround) {
  VoxelRock rock = emptyRock(12, 12, 20);
  fill(rock, {3, 3, 10}, {7, 8, 13}, Material::Rock, 2.5f);
  rock.integrity.set(rock.layout.index(3, 3, 10), 0.25f);
  RockfallSolver solver(rock.layout);
  const RockfallOutcome out = solver.apply(rock, RockfallMode::Drop, {}, true);
  EXPECT_EQ(out.fallen, 4u * 5u * 3u);
  EXPECT_EQ(at(rock, 3, 3, 0), Material::Rock);
  EXPECT_EQ(at(rock, 6, 7, 2), Material::Rock);
  EXPECT_EQ(at(rock, 6, 7, 3), Material::Air);
  EXPECT_EQ(at(rock, 3, 3, 10), Material::Air);
  // Drop keeps the rock's own durability and integrity.
  EXPECT_EQ(rock.durability[rock.layout.index(5, 5, 1)], 2.5f);
  EXPECT_EQ(rock.integrity[rock.layout.index(3, 3, 0)], 0.25f);
  EXPECT_TRUE(nothingFloats(rock));
  EXPECT_EQ(solver.apply(rock, RockfallMode::Drop, {}, true).fallen, 0u);
}

// Rows of random runs, long and short, air and solid, starting anywhere in a word: the labelling's
// run finder (eight cells at a time) finds the same floating cells as a plain flood fill.
TEST(Rockfall, EveryFloatingCellOfRandomRowsFalls) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 6; ++trial) {
    VoxelRock rock = emptyRock(37 + 11 * trial, 9, 14);
    const GridLayout& g = rock.layout;
    std::uniform_int_distribution<int> length(1, trial % 2 ? 30 : 6), percent(0, 99);
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx;) {
          const int end = std::min(g.nx, x + length(random));
          const Material m = percent(random) < 45 ? Material::Rock : Material::Air;
          for (; x < end; ++x) rock.material[g.index(x, y, z)] = m;
        }
    const std::size_t floating = floatingCount(rock);
    ASSERT_GT(floating, 0u);
    RockfallSolver solver(g);
    EXPECT_EQ(solver.apply(rock, RockfallMode::Drop, {}, true).fallen, floating) << "trial " << trial;
    EXPECT_TRUE(test::nothingFloats(rock));
  }
}

TEST(Rockfall, ABlockOnAThinPillarFallsWhenThePillarGoes) {
  VoxelRock rock = emptyRock(12, 12, 24);
  fill(rock, {5, 5, 0}, {6, 6, 10}, Material::Rock);   // the pillar
  fill(rock, {3, 3, 10}, {8, 8, 13}, Material::Rock);  // the block on it
  RockfallSolver solver(rock.layout);
  EXPECT_EQ(solver.apply(rock, RockfallMode::Drop, {}, true).fallen, 0u);

  // Cutting one voxel of the pillar: the local test must notice, and the block
  // with the pillar's upper part drops one voxel onto the stub.
  const Cell cut = Cell(rock.layout.index(5, 5, 4));
  rock.material[cut] = Material::Air;
  const RockfallOutcome out = solver.apply(rock, RockfallMode::Drop, {cut}, false);
  EXPECT_TRUE(out.labelled);
  EXPECT_EQ(out.fallen, 5u + 25u * 3u);
  EXPECT_EQ(at(rock, 5, 5, 4), Material::Rock);
  EXPECT_EQ(at(rock, 3, 3, 9), Material::Rock);
  EXPECT_EQ(at(rock, 3, 3, 12), Material::Air);
  EXPECT_TRUE(nothingFloats(rock));

  // Removing the whole pillar: the block lands on the ground.
  std::vector<Cell> pillar;
  for (int z = 0; z < 9; ++z) {
    pillar.push_back(Cell(rock.layout.index(5, 5, z)));
    rock.material[pillar.back()] = Material::Air;
  }
  EXPECT_EQ(solver.apply(rock, RockfallMode::Drop, pillar, false).fallen, 75u);
  EXPECT_EQ(at(rock, 3, 3, 0), Material::Rock);
  EXPECT_EQ(at(rock, 7, 7, 2), Material::Rock);
  EXPECT_TRUE(nothingFloats(rock));
}

TEST(Rockfall, RemovalThatCutsNothingNeedsNoLabelling) {
  VoxelRock rock = emptyRock(16, 16, 16);
  fill(rock, {2, 2, 0}, {14, 14, 12}, Material::Rock);
  RockfallSolver solver(rock.layout);
  solver.apply(rock, RockfallMode::Drop, {}, true);
  // Nibble a corner and a face: everything stays connected.
  std::vector<Cell> removed = {Cell(rock.layout.index(2, 2, 11)), Cell(rock.layout.index(3, 2, 11)),
                               Cell(rock.layout.index(8, 2, 5))};
  for (Cell c : removed) rock.material[c] = Material::Air;
  const RockfallOutcome out = solver.apply(rock, RockfallMode::Drop, removed, false);
  EXPECT_FALSE(out.labelled);
  EXPECT_EQ(out.fallen, 0u);
}

TEST(Rockfall, TwoBlocksFallingInOneCycleLandOnEachOther) {
  VoxelRock rock = emptyRock(12, 12, 30);
  fill(rock, {2, 2, 8}, {8, 8, 10}, Material::Rock);          // lower, wide
  fill(rock, {4, 4, 18}, {6, 6, 22}, Material::Rock);         // upper, narrow, above it
  fill(rock, {9, 9, 12}, {11, 11, 13}, Material::Colluvium);  // a loose pile, elsewhere
  const std::size_t before = solidCount(rock);
  RockfallSolver solver(rock.layout);
  const RockfallOutcome out = solver.apply(rock, RockfallMode::Drop, {}, true);
  EXPECT_EQ(out.fallen, 72u + 16u + 4u);
  EXPECT_EQ(solidCount(rock), before);  // nothing overlapped, nothing lost
  EXPECT_EQ(at(rock, 2, 2, 0), Material::Rock);
  EXPECT_EQ(at(rock, 4, 4, 2), Material::Rock);  // the upper block sits on the lower one
  EXPECT_EQ(at(rock, 5, 5, 5), Material::Rock);
  EXPECT_EQ(at(rock, 5, 5, 6), Material::Air);
  EXPECT_EQ(at(rock, 9, 9, 0), Material::Colluvium);
  EXPECT_TRUE(nothingFloats(rock));
}

TEST(Rockfall, CrumbleTurnsFallenRockIntoColluviumAndOffLeavesItFloating) {
  VoxelRock crumbled = emptyRock(10, 10, 20);
  fill(crumbled, {3, 3, 10}, {6, 6, 12}, Material::Rock);
  VoxelRock floating = crumbled;
  RockfallSolver solver(crumbled.layout);
  const RockfallOutcome out = solver.apply(crumbled, RockfallMode::Crumble, {}, true);
  EXPECT_EQ(out.crumbled, 18u);
  EXPECT_EQ(crumbled.count(Material::Rock), 0u);
  EXPECT_EQ(crumbled.count(Material::Colluvium), 18u);
  EXPECT_EQ(at(crumbled, 3, 3, 0), Material::Colluvium);

  EXPECT_EQ(solver.apply(floating, RockfallMode::Off, {}, true).fallen, 0u);
  EXPECT_EQ(at(floating, 3, 3, 10), Material::Rock);
  EXPECT_FALSE(nothingFloats(floating));
}

TEST(Rockfall, IsOffWithoutTheGround) {
  // A free-floating block (ground off) stays where it is: nothing to fall onto.
  Preset p = test::cubePreset(3.0, 30, 0.3);
  p.shape.kind = BoxShape{{1.0, 1.0, 1.0}};
  p.shape.center = Vec3d{1.5, 1.5, 1.0};
  p.rockfall.mode = RockfallMode::Drop;
  p.colluvium.yield = 0.5;
  p.stop.cycles = 3;
  const VoxelRock start = buildInitialRock(resolveShape(p), p);
  const WeatheringResult result = weatherRock(start, p);
  for (const auto& c : result.cycles) {
    EXPECT_EQ(c.fallen, 0u);
    EXPECT_EQ(c.colluvium, 0u);
  }
  // With the ground, the same block falls in the first cycle.
  p.grid.ground = true;
  const WeatheringResult grounded = weatherRock(buildInitialRock(resolveShape(p), p), p);
  EXPECT_GT(grounded.cycles.front().fallen, 900u);
  EXPECT_TRUE(nothingFloats(grounded.rock));
}

TEST(Rockfall, NothingFloatsAfterAnyCycle) {
  // A property over seeds and both modes: the cap topples or undercuts at
  // different times, pieces fall and crumble, colluvium piles and is removed.
  std::size_t total_fallen = 0;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    for (RockfallMode mode : {RockfallMode::Drop, RockfallMode::Crumble}) {
      const Preset p = neckPreset(seed, mode);
      WeatheringSimulation sim(buildInitialRock(resolveShape(p), p), p);
      while (!sim.finished()) {
        const CycleStats stats = sim.step();
        total_fallen += stats.fallen;
        ASSERT_TRUE(nothingFloats(sim.rock())) << "seed " << seed << " cycle " << stats.cycle;
      }
    }
  }
  EXPECT_GT(total_fallen, 0u) << "the property test should include real rockfalls";
}

TEST(Rockfall, TheCapOfAWeatheredNeckFallsThroughTheSimulation) {
  const Preset p = neckPreset(1, RockfallMode::Drop);
  const WeatheringResult result = weatherRock(buildInitialRock(resolveShape(p), p), p);
  std::size_t fallen = 0;
  for (const auto& c : result.cycles) fallen += c.fallen;
  EXPECT_GT(fallen, 100u);
  EXPECT_TRUE(nothingFloats(result.rock));
}

}  // namespace
}  // namespace rockbake
