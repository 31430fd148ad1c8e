// Rockfall and colluvium (docs/model.md §6, §7).
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <numbers>

#include "sim/colluvium.h"
#include "sim/rockfall.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

using Cell = std::uint32_t;

VoxelRock emptyRock(int nx, int ny, int nz) {
  VoxelRock rock;
  rock.layout.nx = nx, rock.layout.ny = ny, rock.layout.nz = nz;
  rock.layout.h = 0.1;
  rock.layout.ground = true;
  rock.material.assign(rock.layout.cellCount(), Material::Air);
  rock.integrity = RowSpans(rock.layout, 1.f);
  rock.durability = RowSpans(rock.layout, 0.f);
  return rock;
}

void fill(VoxelRock& rock, std::array<int, 3> lo, std::array<int, 3> hi, Material m, float durability = 1.f) {
  for (int z = lo[2]; z < hi[2]; ++z)
    for (int y = lo[1]; y < hi[1]; ++y)
      for (int x = lo[0]; x < hi[0]; ++x) {
        const std::size_t i = rock.layout.index(x, y, z);
        rock.material[i] = m;
        rock.durability.set(i, m == Material::Rock ? durability : 0.f);
      }
}

Material at(const VoxelRock& rock, int x, int y, int z) {
  return rock.material[rock.layout.index(x, y, z)];
}

std::size_t solidCount(const VoxelRock& rock) {
  return rock.material.size() - rock.count(Material::Air);
}

// Independent check: every solid voxel is 6-connected to the layer z = 0.
bool nothingFloats(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::vector<std::uint8_t> reached(g.cellCount(), 0);
  std::deque<std::array<int, 3>> queue;
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x)
      if (at(rock, x, y, 0) != Material::Air) reached[g.index(x, y, 0)] = 1, queue.push_back({x, y, 0});
  while (!queue.empty()) {
    const auto [x, y, z] = queue.front();
    queue.pop_front();
    const int d[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    for (const auto& o : d) {
      const int a = x + o[0], b = y + o[1], c = z + o[2];
      if (!g.contains(a, b, c) || at(rock, a, b, c) == Material::Air || reached[g.index(a, b, c)]) continue;
      reached[g.index(a, b, c)] = 1;
      queue.push_back({a, b, c});
    }
  }
  for (std::size_t i = 0; i < reached.size(); ++i)
    if (rock.material[i] != Material::Air && !reached[i]) return false;
  return true;
}

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

// A preset that weathers a rock with a soft neck, rockfall and colluvium on.
Preset neckPreset(std::uint64_t seed, RockfallMode mode) {
  Preset p = test::cubePreset(3.0, 36, 0.25);
  p.seed = seed;
  p.grid.size = {3.0, 3.0, 4.0};
  p.grid.ground = true;
  p.shape.kind = CylinderShape{0.9, 3.6};
  p.durability.graph.points = {{0.0, 1.5}, {0.35, 0.35}, {0.55, 0.35}, {0.65, 4.0}, {1.0, 4.0}};
  p.durability.graph.noise = {NoiseParams{0.3, 0.5, 2}, std::nullopt, std::nullopt, std::nullopt};
  p.bubbles[0].cavernous = 0.5;
  p.rockfall.mode = mode;
  p.colluvium = {0.6, 35.0, 0.05};
  p.stop.cycles = 40;
  return p;
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

// The model keeps its own record of which cells are solid; changes made
// elsewhere reach it through noteChanged. A unit dropped down a column lands
// on what is there now, not on what was there when the record was made.
TEST(Colluvium, UnitsLandOnTheRockAsItIsAfterChangesAreNoted) {
  VoxelRock rock = emptyRock(9, 9, 20);
  fill(rock, {4, 4, 0}, {5, 5, 10}, Material::Rock);  // a pillar 10 cells tall
  ColluviumModel model(rock.layout, {1.0, 35.0, 0.0}, 1);
  const Cell above = Cell(rock.layout.index(4, 4, 15));
  std::vector<Cell> changed, unstable;
  ASSERT_EQ(model.deposit(rock, {above}, changed, unstable), 1u);
  EXPECT_EQ(changed.back(), Cell(rock.layout.index(4, 4, 10)));  // on the pillar's top
  // The pillar's upper half and the unit on it go, as a fall would take them.
  std::vector<Cell> gone;
  for (int z = 5; z <= 10; ++z) {
    gone.push_back(Cell(rock.layout.index(4, 4, z)));
    rock.material[gone.back()] = Material::Air;
  }
  model.noteChanged(rock, gone);
  ASSERT_EQ(model.deposit(rock, {above}, changed, unstable), 1u);
  EXPECT_EQ(changed.back(), Cell(rock.layout.index(4, 4, 5)));  // on the shortened pillar
}

TEST(Rockfall, TheCapOfAWeatheredNeckFallsThroughTheSimulation) {
  const Preset p = neckPreset(1, RockfallMode::Drop);
  const WeatheringResult result = weatherRock(buildInitialRock(resolveShape(p), p), p);
  std::size_t fallen = 0;
  for (const auto& c : result.cycles) fallen += c.fallen;
  EXPECT_GT(fallen, 100u);
  EXPECT_TRUE(nothingFloats(result.rock));
}

// Heights of the colluvium columns on flat ground (0 where none).
std::vector<int> pileHeights(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::vector<int> heights(std::size_t(g.nx) * std::size_t(g.ny), 0);
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (at(rock, x, y, z) == Material::Colluvium) heights[std::size_t(x + g.nx * y)] = z + 1;
  return heights;
}

// Drops `units` of colluvium at the centre column from high up and settles it.
VoxelRock pourPile(double talus_angle, int units) {
  VoxelRock rock = emptyRock(41, 41, 40);
  ColluviumModel model(rock.layout, {1.0, talus_angle, 0.0}, 1);
  std::vector<Cell> changed, unstable, vacated;
  for (int i = 0; i < units; ++i) {
    // One decimated voxel at a time, high above the centre.
    model.deposit(rock, {Cell(rock.layout.index(20, 20, 39))}, changed, unstable);
    model.settle(rock, unstable, changed, vacated);
  }
  return rock;
}

TEST(Colluvium, PilesKeepTheirTalusAngle) {
  for (double angle : {30.0, 45.0, 60.0}) {
    const VoxelRock rock = pourPile(angle, 600);
    EXPECT_EQ(rock.count(Material::Colluvium), 600u);
    const std::vector<int> h = pileHeights(rock);
    const double slope = std::tan(angle * std::numbers::pi / 180.0);
    const GridLayout& g = rock.layout;
    for (int y = 1; y < g.ny - 1; ++y)
      for (int x = 1; x < g.nx - 1; ++x)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const double distance = (dx != 0 && dy != 0) ? std::numbers::sqrt2 : 1.0;
            const int step = h[std::size_t(x + g.nx * y)] - h[std::size_t(x + dx + g.nx * (y + dy))];
            ASSERT_LE(step, slope * distance + 1.0 + 1e-9) << "angle " << angle << " at " << x << "," << y;
          }
  }
  // A steeper angle gives a taller, narrower pile from the same debris.
  const std::vector<int> shallow = pileHeights(pourPile(25.0, 600));
  const std::vector<int> steep = pileHeights(pourPile(65.0, 600));
  const auto peak = [](const std::vector<int>& h) { return *std::max_element(h.begin(), h.end()); };
  const auto footprint = [](const std::vector<int>& h) {
    return std::count_if(h.begin(), h.end(), [](int v) { return v > 0; });
  };
  EXPECT_GT(peak(steep), peak(shallow) + 2);
  EXPECT_LT(footprint(steep), footprint(shallow));
}

TEST(Colluvium, IsConservedCycleByCycle) {
  const Preset p = neckPreset(2, RockfallMode::Crumble);
  WeatheringSimulation sim(buildInitialRock(resolveShape(p), p), p);
  std::size_t colluvium = 0, decimated = 0, deposited = 0, removed = 0;
  while (!sim.finished()) {
    const CycleStats c = sim.step();
    // What there is = what there was + what was made − what was carried away.
    EXPECT_EQ(c.colluvium, colluvium + c.deposited + c.crumbled - c.removed) << "cycle " << c.cycle;
    colluvium = c.colluvium;
    decimated += c.decimated;
    deposited += c.deposited;
    removed += c.removed;
  }
  // Created = yield × decimated, up to the accumulators' remainders (yield
  // is held in fixed point, exact to 2^-24 of a voxel per decimated voxel).
  EXPECT_NEAR(double(deposited) + sim.pendingColluvium(), p.colluvium.yield * double(decimated),
              double(decimated) / double(ColluviumModel::kUnit));
  EXPECT_GT(deposited, 0u);
  EXPECT_GT(removed, 0u);
}

TEST(Colluvium, ShieldsTheRockItCovers) {
  VoxelRock rock = emptyRock(30, 14, 12);
  rock.layout.margin = 1;
  fill(rock, {3, 4, 0}, {9, 10, 6}, Material::Rock);    // exposed block
  fill(rock, {18, 4, 0}, {24, 10, 6}, Material::Rock);  // buried block
  fill(rock, {16, 2, 0}, {26, 12, 8}, Material::Colluvium);
  fill(rock, {18, 4, 0}, {24, 10, 6}, Material::Rock);
  Preset p = test::cubePreset(3.0, 30, 0.3);
  p.grid.ground = true;
  p.colluvium.yield = 0.0;
  p.stop.cycles = 3;
  WeatheringSimulation sim(rock, p);
  while (!sim.finished()) sim.step();
  const VoxelRock& after = sim.rock();
  float buried_min = 1.f, exposed_min = 1.f;
  for (std::size_t i = 0; i < after.material.size(); ++i) {
    const int x = int(i % 30);
    if (rock.material[i] != Material::Rock) continue;
    (x < 15 ? exposed_min : buried_min) =
        std::min(x < 15 ? exposed_min : buried_min, after.material[i] == Material::Rock ? after.integrity[i] : 0.f);
  }
  EXPECT_EQ(buried_min, 1.f);
  EXPECT_LT(exposed_min, 1.f);
}

}  // namespace
}  // namespace rockbake
