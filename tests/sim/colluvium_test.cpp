// Colluvium (docs/model.md §7): deposit, settling, removal, conservation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>

#include <tbb/task_arena.h>

#include "core/hash.h"
#include "debris_fixtures.h"
#include "inputs/resolve_shape.h"
#include "preset/load_preset.h"
#include "sim/colluvium.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

using Cell = std::uint32_t;
using test::at;
using test::emptyRock;
using test::fill;
using test::neckPreset;

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

// Drops `units` of colluvium at the centre column from high up, `batch` at a
// time (a column of them, stacked), settling after each batch. The pile
// spreads over four settling tiles.
VoxelRock pourPile(double talus_angle, int units, int batch = 1) {
  VoxelRock rock = emptyRock(41, 41, 40);
  ColluviumModel model(rock.layout, {1.0, talus_angle, 0.0}, 1);
  std::vector<Cell> changed, unstable, vacated;
  for (int poured = 0; poured < units; poured += batch) {
    const std::vector<Cell> decimated(std::size_t(std::min(batch, units - poured)),
                                      Cell(rock.layout.index(20, 20, 39)));
    model.deposit(rock, decimated, changed, unstable);
    model.settle(rock, unstable, changed, vacated);
  }
  return rock;
}

TEST(Colluvium, PilesKeepTheirTalusAngle) {
  for (const auto& [angle, batch] :
       std::vector<std::pair<double, int>>{{30.0, 1}, {45.0, 1}, {60.0, 1}, {30.0, 20}, {45.0, 20}, {60.0, 20}}) {
    const VoxelRock rock = pourPile(angle, 600, batch);
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
            ASSERT_LE(step, slope * distance + 1.0 + 1e-9)
                << "angle " << angle << ", " << batch << " at a time, at " << x << "," << y;
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

// An apron that reaches the grid's side runs on past it (docs/model.md §7, "At the grid's side"):
// what would slide off leaves the grid, so the pile slopes down to the side instead of standing
// there as a wall, and every unit is either in the grid or counted as gone.
TEST(Colluvium, AnApronThatReachesTheGridsSideRunsOnPastIt) {
  VoxelRock rock = emptyRock(31, 31, 40);
  ColluviumModel model(rock.layout, {1.0, 35.0, 0.0}, 1);
  std::vector<Cell> changed, unstable, vacated;
  std::size_t left = 0;
  const int units = 6000;  // a 35° cone of this volume is about 20 voxels in radius: past the sides
  for (int poured = 0; poured < units; poured += 20) {
    model.deposit(rock, std::vector<Cell>(20, Cell(rock.layout.index(15, 15, 39))), changed, unstable);
    left += model.settle(rock, unstable, changed, vacated);
  }
  EXPECT_GT(left, 0u);
  EXPECT_EQ(rock.count(Material::Colluvium) + left, std::size_t(units));
  // On the outermost ring of columns the pile stands no higher than a slope at the talus angle
  // down to the ground a column beyond allows (the cone's own height there is about 8 voxels).
  const std::vector<int> heights = pileHeights(rock);
  const int allowed = 1 + int(std::ceil(std::tan(35.0 * std::numbers::pi / 180.0) * std::numbers::sqrt2));
  for (int i = 0; i < 31; ++i)
    for (const auto& [x, y] : {std::pair{i, 0}, {i, 30}, {0, i}, {30, i}})
      ASSERT_LE(heights[std::size_t(x + 31 * y)], allowed) << "column " << x << ", " << y;
  EXPECT_GT(*std::max_element(heights.begin(), heights.end()), 10);
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

// Independent checks of the settling rule's fixed point (docs/model.md §7):
// the first colluvium voxel found over air, or that would still slide, as
// "x,y,z" (empty when every voxel is at rest).
std::string hangingOverAir(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  for (int z = 1; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (at(rock, x, y, z) == Material::Colluvium && at(rock, x, y, z - 1) == Material::Air)
          return std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z);
  return {};
}

std::string wouldSlide(const VoxelRock& rock, double talus_angle) {
  const GridLayout& g = rock.layout;
  const double slope = std::tan(talus_angle * std::numbers::pi / 180.0);
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        if (at(rock, x, y, z) != Material::Colluvium) continue;
        if (z + 1 < g.nz && at(rock, x, y, z + 1) != Material::Air) continue;  // covered
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if ((dx == 0 && dy == 0) || !g.contains(x + dx, y + dy, z)) continue;
            if (at(rock, x + dx, y + dy, z) != Material::Air) continue;
            int rest = z;
            while (rest > 0 && at(rock, x + dx, y + dy, rest - 1) == Material::Air) --rest;
            const double distance = (dx != 0 && dy != 0) ? std::numbers::sqrt2 : 1.0;
            if (double(z - rest) > slope * distance)
              return std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z);
          }
      }
  return {};
}

// A scene where settling has much to do across many tiles: a plateau of rock
// across 4 × 4 tiles with a ledge at its side, debris dropped all over its top
// and stacked by a tile corner, and a loose heap hanging over air. Nothing is
// settled yet; `unstable` lists what settle() must look at.
constexpr int kSceneX = 150, kSceneY = 140, kSceneZ = 40;
struct SettleScene {
  VoxelRock rock;
  std::vector<Cell> unstable;
};

SettleScene settleScene(ColluviumModel& model) {
  SettleScene s{emptyRock(kSceneX, kSceneY, kSceneZ), {}};
  VoxelRock& rock = s.rock;
  fill(rock, {24, 20, 0}, {120, 116, 14}, Material::Rock);   // the plateau
  fill(rock, {120, 60, 0}, {132, 76, 6}, Material::Rock);    // a ledge at its side
  fill(rock, {5, 5, 10}, {12, 9, 14}, Material::Colluvium);  // a heap over air: it falls
  std::vector<Cell> decimated, changed;
  for (int y = 20; y < 116; y += 2)
    for (int x = 24; x < 120; x += 2)
      for (int i = 0; i < 4; ++i) decimated.push_back(Cell(rock.layout.index(x, y, kSceneZ - 1)));
  for (int i = 0; i < 24; ++i) decimated.push_back(Cell(rock.layout.index(64, 64, kSceneZ - 1)));  // by a tile corner
  std::sort(decimated.begin(), decimated.end());
  model.deposit(rock, decimated, changed, s.unstable);
  for (int z = 10; z < 14; ++z)
    for (int y = 5; y < 9; ++y)
      for (int x = 5; x < 12; ++x) s.unstable.push_back(Cell(rock.layout.index(x, y, z)));
  return s;
}

// The tiles of one phase settle on their own threads: the piles, and what
// settle() reports, are the same at any thread count, with the tiles of
// each phase taken one after another in any order, and whatever the order
// of the voxels handed to it.
TEST(Colluvium, SettlesTheSameAtAnyThreadCountAndInAnyOrder) {
  struct Outcome {
    std::vector<Material> material;
    std::vector<Cell> changed, vacated;
    std::uint64_t work = 0, largest_tiles = 0, two_workers = 0;
    bool operator==(const Outcome&) const = default;
  };
  const auto settleWith = [](int threads, std::uint64_t tile_order, std::uint64_t input_order) {
    const GridLayout layout = emptyRock(kSceneX, kSceneY, kSceneZ).layout;
    ColluviumModel model(layout, {1.0, 35.0, 0.0}, 7);
    SettleScene s = settleScene(model);
    if (input_order != 0) {  // shuffled, with every voxel listed twice
      s.unstable.insert(s.unstable.end(), s.unstable.begin(), s.unstable.end());
      std::sort(s.unstable.begin(), s.unstable.end(),
                [&](Cell a, Cell b) { return counterHash(input_order, 0, 0, a) < counterHash(input_order, 0, 0, b); });
    }
    model.shuffleTiles(tile_order);
    Outcome out;
    tbb::task_arena arena(threads);
    arena.execute([&] { model.settle(s.rock, s.unstable, out.changed, out.vacated); });
    out.material = s.rock.material;
    out.work = model.settleWork().work;
    out.largest_tiles = model.settleWork().largest_tiles;
    out.two_workers = model.settleWork().two_workers;
    return out;
  };
  const Outcome reference = settleWith(1, 0, 0);
  // Enough happened, over enough of the grid, for the order to matter.
  const VoxelRock before = [] {
    ColluviumModel model(emptyRock(kSceneX, kSceneY, kSceneZ).layout, {1.0, 35.0, 0.0}, 7);
    return settleScene(model).rock;
  }();
  std::size_t moved = 0;
  std::vector<int> tiles;
  for (std::size_t c = 0; c < before.material.size(); ++c) {
    moved += before.material[c] == Material::Colluvium && reference.material[c] != Material::Colluvium;
    if (reference.material[c] == Material::Colluvium) {
      const VoxelCoord p = before.layout.coord(c);
      tiles.push_back(p.x / ColluviumModel::kSettleTile + kSceneX * (p.y / ColluviumModel::kSettleTile));
    }
  }
  std::sort(tiles.begin(), tiles.end());
  EXPECT_GT(moved, 5000u);
  EXPECT_GE(std::unique(tiles.begin(), tiles.end()) - tiles.begin(), 12);
  EXPECT_EQ(std::count(reference.material.begin(), reference.material.end(), Material::Colluvium),
            std::count(before.material.begin(), before.material.end(), Material::Colluvium));
  VoxelRock settled = before;
  settled.material = reference.material;
  EXPECT_EQ(hangingOverAir(settled), "");
  EXPECT_EQ(wouldSlide(settled, 35.0), "");
  // The work is counted, and the tiles leave much of it to share: two
  // workers' larger share is well under the whole.
  EXPECT_GT(reference.work, moved);
  EXPECT_LE(reference.largest_tiles, reference.two_workers);
  EXPECT_LT(double(reference.two_workers), 0.75 * double(reference.work));

  for (const auto& [threads, tile_order, input_order] : std::vector<std::tuple<int, std::uint64_t, std::uint64_t>>{
           {2, 0, 0}, {4, 0, 0}, {2, 0, 3}, {1, 1, 0}, {1, 2, 0}, {2, 3, 5}}) {
    const Outcome out = settleWith(threads, tile_order, input_order);
    EXPECT_TRUE(out == reference) << threads << " threads, tile order " << tile_order << ", input order "
                                  << input_order;
  }
}

// Through the whole simulation, with rockfall of both kinds: the same rock at
// one thread and two.
TEST(Colluvium, WeathersTheSameAtOneAndTwoThreads) {
  for (RockfallMode mode : {RockfallMode::Drop, RockfallMode::Crumble}) {
    const Preset p = neckPreset(3, mode);
    std::vector<std::vector<Material>> materials;
    for (int threads : {1, 2}) {
      tbb::task_arena arena(threads);
      arena.execute([&] { materials.push_back(weatherRock(buildInitialRock(resolveShape(p), p), p).rock.material); });
    }
    EXPECT_GT(std::count(materials[0].begin(), materials[0].end(), Material::Colluvium), 1000);
    EXPECT_TRUE(materials[0] == materials[1]) << (mode == RockfallMode::Drop ? "drop" : "crumble");
  }
}

// The shipped presets with the largest piles, at their own resolution: their
// grids span 3 × 3 and 4 × 4 settling tiles, so each phase settles several
// tiles at once. The same rock at one thread and two, every voxel at rest.
TEST(Colluvium, ShippedPilesWeatherTheSameAtOneAndTwoThreads) {
  for (const char* name : {"goblin", "talus-cliff"}) {
    const Preset p = loadPreset(test::sourceDir() / "presets" / (std::string(name) + ".yaml"));
    const VoxelRock initial = buildInitialRock(resolveShape(p), p);
    ASSERT_GT(initial.layout.nx, 2 * ColluviumModel::kSettleTile) << name;
    ASSERT_GT(initial.layout.ny, 2 * ColluviumModel::kSettleTile) << name;
    std::vector<VoxelRock> rocks;
    for (int threads : {1, 2}) {
      tbb::task_arena arena(threads);
      arena.execute([&] { rocks.push_back(weatherRock(initial, p).rock); });
    }
    EXPECT_GT(rocks[0].count(Material::Colluvium), 30000u) << name;
    EXPECT_TRUE(rocks[0].material == rocks[1].material) << name << ": 1 vs 2 threads differ";
    EXPECT_EQ(hangingOverAir(rocks[1]), "") << name;
    EXPECT_EQ(wouldSlide(rocks[1], p.colluvium.talus_angle), "") << name;
  }
}

// Whatever a cycle did (decimation under a pile, removal, a fall that carried
// colluvium with it, crumbled rock), colluvium ends it at rest: on something,
// and no steeper than its talus angle. Both checks are made after every cycle.
TEST(Colluvium, EveryVoxelIsAtRestAfterEveryCycle) {
  std::size_t checked = 0;
  for (double talus : {35.0, 60.0})
    for (std::uint64_t seed : {1u, 2u, 3u, 4u})
      for (RockfallMode mode : {RockfallMode::Drop, RockfallMode::Crumble}) {
        Preset p = neckPreset(seed, mode);
        p.colluvium.talus_angle = talus;
        WeatheringSimulation sim(buildInitialRock(resolveShape(p), p), p);
        while (!sim.finished()) {
          const CycleStats stats = sim.step();
          const std::string where = "talus " + std::to_string(int(talus)) + ", seed " + std::to_string(seed) +
                                    (mode == RockfallMode::Drop ? ", drop" : ", crumble") + ", cycle " +
                                    std::to_string(stats.cycle) + ": colluvium at ";
          const std::string over_air = hangingOverAir(sim.rock());
          ASSERT_EQ(over_air, "") << where << over_air << " is over air";
          const std::string sliding = wouldSlide(sim.rock(), talus);
          ASSERT_EQ(sliding, "") << where << sliding << " is steeper than its talus angle";
          checked += stats.colluvium;
        }
      }
  EXPECT_GT(checked, 100000u);
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

// A preset whose apron would reach the grid's side (docs/model.md §7, "At the grid's side"): a
// broad column on a grid barely wider than it, weathered with a full yield and no removal. The
// apron runs on past the side instead of standing against it, checked on the voxels: on the
// outermost ring of columns it stands no higher than the talus slope down to the ground beyond
// allows, and every voxel that left is counted in `removed`, so the cycles still add up.
TEST(Colluvium, APresetsApronAtTheGridsSideIsNotCutOff) {
  Preset p = test::neckPreset(3, RockfallMode::Drop);
  p.grid.size = {2.2, 2.2, 4.0};
  p.shape.kind = CylinderShape{1.0, 3.6};
  p.colluvium = {1.0, 35.0, 0.0};
  p.stop.cycles = 30;
  const WeatheringResult r = weatherRock(buildInitialRock(resolveShape(p), p), p);
  const GridLayout& g = r.rock.layout;
  std::size_t removed = 0, deposited = 0, crumbled = 0;
  for (const CycleStats& c : r.cycles) removed += c.removed, deposited += c.deposited, crumbled += c.crumbled;
  EXPECT_GT(removed, 0u);  // some slid off: the apron reached the side
  EXPECT_EQ(r.rock.count(Material::Colluvium), deposited + crumbled - removed);
  const int allowed = 1 + int(std::ceil(std::tan(35.0 * std::numbers::pi / 180.0) * std::numbers::sqrt2));
  const std::vector<int> heights = pileHeights(r.rock);
  for (int i = 0; i < g.nx; ++i)
    for (const auto& [x, y] : {std::pair{i, 0}, {i, g.ny - 1}})
      ASSERT_LE(heights[std::size_t(x + g.nx * y)], allowed) << "column " << x << ", " << y;
  for (int j = 0; j < g.ny; ++j)
    for (const auto& [x, y] : {std::pair{0, j}, {g.nx - 1, j}})
      ASSERT_LE(heights[std::size_t(x + g.nx * y)], allowed) << "column " << x << ", " << y;
}

}  // namespace
}  // namespace rockbake
