// Bubble counting and weathering cycles (figures in bench/README.md).
//
//   BM_AlphaNaive/R, BM_AlphaRows/R/path, BM_AlphaRuns/R/path: α for a
//     radius-R sphere bubble (R = 6, 19) on the exposed voxels of a weathering
//     96³ cube: the naive triple loop, the bit-row counter one voxel at a
//     time, and runs of voxels along x as the simulation counts them, on the
//     portable (0) and AVX-512 (1) paths. Every count is checked against the
//     naive loop before timing.
//   BM_Cycle/N/threads: one weathering cycle of an N³ cube.
//   BM_CycleFixedRock/N: one cycle of the same 32³ rock in an N³ grid: the
//     cost must follow the exposed voxels, not the grid's volume.
//   BM_CycleWithDebris/N/threads: a cycle of an N³ cube on the ground with
//     rockfall and colluvium on; counters give each phase's share, and how
//     far settling's tiles let 2 threads (settle_2t_bound) and any number
//     (settle_bound) speed settling up.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <iostream>

#include <tbb/global_control.h>

#include "sim/bubble.h"
#include "sim/curvature.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

namespace rockbake {
namespace {

Preset cube(int cube_voxels, int grid_voxels, double radius_voxels) {
  Preset p;
  p.name = "bench";
  const double h = 0.1;
  p.grid.size = {grid_voxels * h, grid_voxels * h, grid_voxels * h};
  p.grid.resolution = grid_voxels;
  p.grid.ground = false;
  p.shape.kind = BoxShape{{cube_voxels * h, cube_voxels * h, cube_voxels * h}};
  p.shape.center = Vec3d{grid_voxels * h / 2, grid_voxels * h / 2, (grid_voxels - cube_voxels) * h / 2};
  BubbleBand band;
  band.bubble.kind = BubbleSpec::Kind::Sphere;
  band.bubble.extents = {radius_voxels * h, 0, 0};
  p.bubbles = {band};
  p.response = {ResponseParams::Kind::Threshold, 0.5, {}};
  p.rockfall.mode = RockfallMode::Off;
  p.stop.cycles = 1000000;
  return p;
}

// A 96³ cube after 20 cycles, and its exposed voxels.
struct WeatheredRock {
  VoxelRock rock;
  std::vector<std::array<int, 3>> exposed;
};

const WeatheredRock& weatheredCube() {
  static const WeatheredRock weathered = [] {
    const Preset p = cube(96, 96, 6.0);
    WeatheringSimulation sim(buildInitialRock(resolveShape(p), p), p);
    for (int i = 0; i < 20; ++i) sim.step();
    WeatheredRock w{sim.release(), {}};
    const GridLayout& g = w.rock.layout;
    const auto air = [&](int x, int y, int z) {
      return !g.contains(x, y, z) || w.rock.material[g.index(x, y, z)] == Material::Air;
    };
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x)
          if (w.rock.material[g.index(x, y, z)] == Material::Rock &&
              (air(x - 1, y, z) || air(x + 1, y, z) || air(x, y - 1, z) || air(x, y + 1, z) || air(x, y, z - 1) ||
               air(x, y, z + 1)))
            w.exposed.push_back({x, y, z});
    return w;
  }();
  return weathered;
}

void BM_AlphaNaive(benchmark::State& state) {
  const WeatheredRock& w = weatheredCube();
  const Bubble bubble = makeSphereBubble(double(state.range(0)));
  for (auto _ : state) {
    long total = 0;
    for (const auto& v : w.exposed) total += naiveCountAir(w.rock, bubble, v[0], v[1], v[2]);
    benchmark::DoNotOptimize(total);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(w.exposed.size()));
}

// The exposed voxels grouped as the simulation groups them: up to 8 of one
// x-row, at most 7 apart.
struct Run {
  int x0, y, z, n;
  std::uint8_t dx[AirField::kRunWidth];
};
std::vector<Run> exposedRuns(const WeatheredRock& w) {
  std::vector<Run> runs;
  for (std::size_t i = 0; i < w.exposed.size();) {
    Run r{w.exposed[i][0], w.exposed[i][1], w.exposed[i][2], 1, {0}};
    while (r.n < AirField::kRunWidth && i + std::size_t(r.n) < w.exposed.size()) {
      const auto& v = w.exposed[i + std::size_t(r.n)];
      if (v[1] != r.y || v[2] != r.z || v[0] - r.x0 >= AirField::kRunWidth) break;
      r.dx[r.n++] = std::uint8_t(v[0] - r.x0);
    }
    runs.push_back(r);
    i += std::size_t(r.n);
  }
  return runs;
}

void checkAgainstNaive(const WeatheredRock& w, const Bubble& bubble, const AirField& field,
                       const AirField::BoundBubble& bound, AlphaPath path) {
  std::size_t i = 0;
  for (const Run& r : exposedRuns(w)) {
    int counts[AirField::kRunWidth];
    field.countAirRun(path, bound, r.x0, r.y, r.z, r.dx, r.n, counts);
    for (int k = 0; k < r.n; ++k, ++i) {
      const int naive = naiveCountAir(w.rock, bubble, r.x0 + r.dx[k], r.y, r.z);
      const std::uint8_t zero[1] = {0};
      int one = -1;
      field.countAirRun(path, bound, r.x0 + r.dx[k], r.y, r.z, zero, 1, &one);
      if (counts[k] != naive || one != naive || field.countAir(bound, r.x0 + r.dx[k], r.y, r.z) != naive) {
        std::cerr << "bit-row count differs from the naive loop (" << alphaPathName(path) << ")\n";
        std::abort();
      }
    }
  }
}

void BM_AlphaRows(benchmark::State& state) {
  const AlphaPath path = state.range(1) == 1 ? AlphaPath::Avx512 : AlphaPath::Portable;
  if (!alphaPathAvailable(path)) {
    state.SkipWithError("this CPU lacks AVX-512F/VPOPCNTDQ");
    return;
  }
  const WeatheredRock& w = weatheredCube();
  const Bubble bubble = makeSphereBubble(double(state.range(0)));
  const AirField field(w.rock, bubble.reach);
  const auto bound = field.bind(bubble);
  checkAgainstNaive(w, bubble, field, bound, path);
  const std::uint8_t zero[1] = {0};
  for (auto _ : state) {
    long total = 0;
    int count = 0;
    for (const auto& v : w.exposed) {
      field.countAirRun(path, bound, v[0], v[1], v[2], zero, 1, &count);
      total += count;
    }
    benchmark::DoNotOptimize(total);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(w.exposed.size()));
  state.counters["exposed"] = double(w.exposed.size());
  state.counters["pieces"] = double(bound.pieces);
}

void BM_AlphaRuns(benchmark::State& state) {
  const AlphaPath path = state.range(1) == 1 ? AlphaPath::Avx512 : AlphaPath::Portable;
  if (!alphaPathAvailable(path)) {
    state.SkipWithError("this CPU lacks AVX-512F/VPOPCNTDQ");
    return;
  }
  const WeatheredRock& w = weatheredCube();
  const Bubble bubble = makeSphereBubble(double(state.range(0)));
  const AirField field(w.rock, bubble.reach);
  const auto bound = field.bind(bubble);
  checkAgainstNaive(w, bubble, field, bound, path);
  const std::vector<Run> runs = exposedRuns(w);
  for (auto _ : state) {
    long total = 0;
    int counts[AirField::kRunWidth];
    for (const Run& r : runs) {
      field.countAirRun(path, bound, r.x0, r.y, r.z, r.dx, r.n, counts);
      for (int k = 0; k < r.n; ++k) total += counts[k];
    }
    benchmark::DoNotOptimize(total);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(w.exposed.size()));
  state.counters["voxels_per_run"] = double(w.exposed.size()) / double(runs.size());
}

// Times cycles of a simulation started fresh for each batch of iterations.
void timeCycles(benchmark::State& state, const Preset& p) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(1)));
  const VoxelRock initial = buildInitialRock(resolveShape(p), p);
  WeatheringSimulation sim(initial, p);
  for (int i = 0; i < 5; ++i) sim.step();  // past the first, atypical cycles
  std::size_t exposed = 0;
  for (auto _ : state) exposed = sim.step().exposed;
  state.counters["exposed"] = double(exposed);
  state.counters["grid_cells"] = double(initial.layout.cellCount());
}

void BM_CycleWithDebris(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(1)));
  const int n = int(state.range(0));
  Preset p = cube(n, n, 6.0);
  p.grid.ground = true;
  p.shape.center = Vec3d{n * 0.05, n * 0.05, 0.0};
  p.response = {ResponseParams::Kind::Power, 1.0, {}};
  p.bubbles[0].cavernous = 0.5;
  p.rockfall.mode = RockfallMode::Drop;
  p.colluvium = {0.5, 35.0, 0.02};
  WeatheringSimulation sim(buildInitialRock(resolveShape(p), p), p);
  for (int i = 0; i < 5; ++i) sim.step();
  double curvature = 0, colluvium = 0, rockfall = 0;
  double settle_work = 0, largest_tiles = 0, two_workers = 0;
  for (auto _ : state) {
    const CycleStats c = sim.step();
    curvature += c.times.seconds("curvature").value_or(0.0), colluvium += c.times.seconds("colluvium").value_or(0.0),
        rockfall += c.times.seconds("rockfall").value_or(0.0);
    settle_work += double(c.settle_work), largest_tiles += double(c.settle_largest_tiles);
    two_workers += double(c.settle_two_workers);
  }
  // What the settling tiles leave to share (deterministic): the speed-up of
  // settling that 2 threads, and any number, could reach at most.
  state.counters["settle_2t_bound"] = settle_work / two_workers;
  state.counters["settle_bound"] = settle_work / largest_tiles;
  const double total = curvature + colluvium + rockfall;
  state.counters["curvature_share"] = curvature / total;
  state.counters["colluvium_share"] = colluvium / total;
  state.counters["rockfall_share"] = rockfall / total;
  state.counters["rockfall_ms"] = 1000.0 * rockfall / double(state.iterations());
}

void BM_Cycle(benchmark::State& state) {
  timeCycles(state, cube(int(state.range(0)), int(state.range(0)), 6.0));
}
void BM_CycleFixedRock(benchmark::State& state) {
  timeCycles(state, cube(32, int(state.range(0)), 6.0));
}

BENCHMARK(BM_AlphaNaive)->Arg(6)->Arg(19)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AlphaRows)->Args({6, 0})->Args({6, 1})->Args({19, 0})->Args({19, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AlphaRuns)->Args({6, 0})->Args({6, 1})->Args({19, 0})->Args({19, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Cycle)->Args({128, 1})->Args({128, 2})->Iterations(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CycleWithDebris)->Args({128, 1})->Args({128, 2})->Iterations(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CycleFixedRock)
    ->Args({64, 1})
    ->Args({128, 1})
    ->Args({256, 1})
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rockbake

BENCHMARK_MAIN();
