// The weathering history the simulation records (docs/model.md §14): when each rock voxel was
// first exposed to air, how long it lay under colluvium, and where rockfall opened the surface;
// kept in checkpoints so that a resume records the same.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "sim/checkpoint_format.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

bool airAt(const VoxelRock& rock, int x, int y, int z) {
  const GridLayout& g = rock.layout;
  if (!g.contains(x, y, z)) return !(z < 0 && g.ground);
  return rock.material[g.index(x, y, z)] == Material::Air;
}

bool faceOnAir(const VoxelRock& rock, int x, int y, int z) {
  for (const auto& o : kFaceNeighbours)
    if (airAt(rock, x + o[0], y + o[1], z + o[2])) return true;
  return false;
}

bool faceOnColluvium(const VoxelRock& rock, int x, int y, int z) {
  const GridLayout& g = rock.layout;
  for (const auto& o : kFaceNeighbours)
    if (g.contains(x + o[0], y + o[1], z + o[2]) &&
        rock.material[g.index(x + o[0], y + o[1], z + o[2])] == Material::Colluvium)
      return true;
  return false;
}

// A cube on the ground with rockfall and colluvium: every part of the history has work.
Preset groundedCube() {
  Preset p = test::cubePreset(3.2, 32, 0.4);
  p.grid.ground = true;
  p.grid.size = {4.8, 4.8, 3.2};
  p.rockfall.mode = RockfallMode::Drop;
  p.colluvium.yield = 0.5;
  p.colluvium.removal = 0.05;
  p.bubbles[0].cavernous = 0.5;
  p.stop.cycles = 8;
  return p;
}

std::vector<std::vector<float>> historyGrids(const VoxelRock& rock) {
  const VoxelHistory& h = rock.history;
  return {h.exposed.toDense(), h.covered.toDense(), h.covered_for.toDense(), h.scarred.toDense()};
}

TEST(History, AVoxelExposedAtCycleKRecordsK) {
  Preset p = test::cubePreset(3.2, 32, 0.4);
  p.stop.cycles = 6;
  WeatheringSimulation sim(buildInitialRock(resolveShape(p), p), p);
  const GridLayout& g = sim.rock().layout;
  // The oracle: the first cycle end at which each rock voxel had a face on air (0: the blockout).
  std::vector<int> first(g.cellCount(), -1);
  const auto observe = [&](int cycle) {
    const VoxelRock& rock = sim.rock();
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x) {
          const std::size_t c = g.index(x, y, z);
          if (first[c] < 0 && rock.material[c] == Material::Rock && faceOnAir(rock, x, y, z)) first[c] = cycle;
        }
  };
  observe(0);
  while (!sim.finished()) observe(sim.step().cycle);
  const VoxelRock& rock = sim.rock();
  EXPECT_EQ(rock.history.cycles, 6);
  std::size_t checked = 0, later = 0;
  for (std::size_t c = 0; c < g.cellCount(); ++c) {
    if (rock.material[c] != Material::Rock) continue;
    ASSERT_EQ(rock.history.exposed[c], float(first[c])) << "cell " << c;
    ++checked;
    later += first[c] > 0;
  }
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(later, 100u);  // voxels uncovered by weathering, not only the blockout's surface
}

TEST(History, RockfallMarksAScarWhereAKnownBlockFell) {
  // A durable wall with a durable block hung from it by a two-voxel neck of very soft rock: the
  // neck goes in the first cycle and the block drops to the ground.
  GridLayout g;
  g.nx = 20, g.ny = 12, g.nz = 20, g.margin = 3, g.h = 0.1, g.domain_height = 2.0, g.ground = true;
  VoxelRock rock;
  rock.layout = g;
  rock.material.assign(g.cellCount(), Material::Air);
  const auto fill = [&](int x0, int x1, int y0, int y1, int z0, int z1) {
    for (int z = z0; z < z1; ++z)
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) rock.material[g.index(x, y, z)] = Material::Rock;
  };
  fill(4, 8, 3, 9, 0, 16);    // the wall
  fill(9, 12, 4, 8, 10, 14);  // the block
  fill(8, 9, 5, 7, 12, 13);   // the neck
  resetRockValues(rock);
  for (std::size_t c = 0; c < g.cellCount(); ++c)
    if (rock.material[c] == Material::Rock) rock.durability.set(c, 100.f);
  rock.durability.set(g.index(8, 5, 12), 1e-4f);
  rock.durability.set(g.index(8, 6, 12), 1e-4f);

  Preset p = test::cubePreset(1.0, 16, 0.2);
  p.grid.ground = true;
  p.rockfall.mode = RockfallMode::Drop;
  p.stop.cycles = 1;
  WeatheringSimulation sim(std::move(rock), p);
  const CycleStats stats = sim.step();
  ASSERT_EQ(stats.decimated, 2u);
  ASSERT_EQ(stats.fallen, 48u);
  const VoxelRock& after = sim.rock();
  const auto scarred = [&](int x, int y, int z) { return after.history.scarred[g.index(x, y, z)]; };
  // The wall's face where the block hung is a scar of cycle 1; the wall's face far below it and
  // its back are not, nor is the block that fell.
  EXPECT_EQ(scarred(7, 5, 12), 1.f);
  EXPECT_EQ(scarred(7, 6, 11), 1.f);
  EXPECT_EQ(scarred(7, 4, 13), 1.f);
  EXPECT_EQ(scarred(7, 5, 5), -1.f);
  EXPECT_EQ(scarred(4, 5, 12), -1.f);
  EXPECT_EQ(after.material[g.index(10, 5, 1)], Material::Rock);  // the block, landed
  EXPECT_EQ(scarred(10, 5, 1), -1.f);
  // The block kept its own record: exposed at the start, as it was.
  EXPECT_EQ(after.history.exposed[g.index(11, 5, 3)], 0.f);
}

TEST(History, ColluviumCoverIsCountedAndLastUntilTheEnd) {
  const Preset p = groundedCube();
  const WeatheringResult result = weatherRock(buildInitialRock(resolveShape(p), p), p);
  const VoxelRock& rock = result.rock;
  const GridLayout& g = rock.layout;
  const float n = float(result.cycles.size());
  std::size_t under = 0, once = 0;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const std::size_t c = g.index(x, y, z);
        if (rock.material[c] != Material::Rock) continue;
        const float until = rock.history.covered[c], cycles = rock.history.covered_for[c];
        if (faceOnColluvium(rock, x, y, z)) {
          ++under;
          ASSERT_EQ(until, n);
          ASSERT_GE(cycles, 1.f);
        }
        if (cycles > 0) {
          ++once;
          ASSERT_LE(cycles, n + 1.f);
          ASSERT_GE(until, 0.f);
        }
        if (cycles == 0) ASSERT_EQ(until, -1.f);
      }
  EXPECT_GT(under, 20u);
  EXPECT_GE(once, under);
}

// The rock under colluvium is kept from the cells that change each cycle, not by a rescan: after
// every cycle, exactly the rock with a face on colluvium records that cycle as its last under it.
TEST(History, CoverIsRecordedExactlyWhereColluviumTouchesEachCycle) {
  const Preset p = groundedCube();  // rockfall drops rock, moving its record; colluvium comes and goes
  WeatheringSimulation simulation(buildInitialRock(resolveShape(p), p), p);
  std::size_t touched = 0, left = 0;
  while (!simulation.finished()) {
    simulation.step();
    const VoxelRock& rock = simulation.rock();
    const GridLayout& g = rock.layout;
    const float k = float(rock.history.cycles);
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x) {
          const std::size_t c = g.index(x, y, z);
          if (rock.material[c] != Material::Rock) continue;
          const bool under = faceOnColluvium(rock, x, y, z);
          ASSERT_EQ(rock.history.covered[c] == k, under) << x << ", " << y << ", " << z << " after cycle " << k;
          touched += under;
          left += !under && rock.history.covered_for[c] > 0;
        }
  }
  EXPECT_GT(touched, 100u);
  EXPECT_GT(left, 0u);  // some rock came out from under the colluvium
}

TEST(History, AResumeFromACheckpointRecordsTheSame) {
  const Preset p = groundedCube();
  const VoxelRock initial = buildInitialRock(resolveShape(p), p);
  const WeatheringResult straight = weatherRock(initial, p);

  WeatheringSimulation first(initial, p);
  for (int k = 0; k < 4; ++k) first.step();
  Checkpoint checkpoint;
  checkpoint.snapshot = first.snapshot();
  checkpoint.preset = nlohmann::json::object();
  const Checkpoint read = parseCheckpoint(checkpointBytes(checkpoint), "test.rbk");
  EXPECT_EQ(read.snapshot.rock.history.cycles, 4);
  WeatheringSimulation resumed(read.snapshot, p);
  while (!resumed.finished()) resumed.step();
  const VoxelRock rock = resumed.release();

  ASSERT_EQ(rock.material, straight.rock.material);
  EXPECT_EQ(historyGrids(rock), historyGrids(straight.rock));
  EXPECT_EQ(rock.history.cycles, straight.rock.history.cycles);
  // The record has something in each grid, so the comparison compares something.
  std::size_t scars = 0, covered = 0;
  for (float v : rock.history.scarred.toDense()) scars += v >= 0;
  for (float v : rock.history.covered_for.toDense()) covered += v > 0;
  EXPECT_GT(covered, 0u);
  (void)scars;
}

TEST(History, TheSameAtOneAndTwoThreads) {
  const Preset p = groundedCube();
  const VoxelRock initial = buildInitialRock(resolveShape(p), p);
  std::vector<std::vector<float>> one, two;
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    one = historyGrids(weatherRock(initial, p).rock);
  }
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    two = historyGrids(weatherRock(initial, p).rock);
  }
  EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace rockbake
