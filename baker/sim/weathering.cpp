#include "sim/weathering.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sim/bubble.h"
#include "sim/colluvium.h"
#include "sim/curvature.h"
#include "sim/durability.h"
#include "sim/response.h"
#include "sim/rockfall.h"

namespace rockbake {
namespace {

using Cell = std::uint32_t;

// The bubble graph bound to one air field: per layer z, which band applies.
struct BubbleGraph {
  std::vector<int> band_of_layer;
  std::vector<BoundEstimator> estimators;
  std::vector<double> spheroidal, cavernous;
  int reach = 0;
};

std::vector<BubbleEstimator> buildEstimators(const SimParams& preset, double h, int& reach) {
  std::vector<BubbleEstimator> estimators;
  reach = 1;  // exposure looks at face neighbours even for sub-voxel bubbles
  for (const auto& band : preset.bubbles) {
    estimators.push_back(makeBubbleEstimator(band.bubble, h));
    reach = std::max(reach, estimators.back().reach);
  }
  return estimators;
}

BubbleGraph bindBubbleGraph(const SimParams& preset, const GridLayout& g, const AirField& field,
                            const std::vector<BubbleEstimator>& estimators) {
  BubbleGraph graph;
  for (std::size_t b = 0; b < preset.bubbles.size(); ++b) {
    graph.estimators.push_back(bindEstimator(field, estimators[b]));
    graph.spheroidal.push_back(preset.bubbles[b].spheroidal);
    graph.cavernous.push_back(preset.bubbles[b].cavernous);
  }
  graph.band_of_layer.resize(std::size_t(g.nz));
  for (int z = 0; z < g.nz; ++z) {
    const double a = g.altitude(z);
    int band = int(preset.bubbles.size()) - 1;  // above the domain: the top band
    for (int b = 0; b < int(preset.bubbles.size()); ++b)
      if (a <= preset.bubbles[std::size_t(b)].up_to) {
        band = b;
        break;
      }
    graph.band_of_layer[std::size_t(z)] = band;
  }
  return graph;
}

// SPEC §2.2: rock with at least one face neighbour of air.
bool isExposed(const VoxelRock& rock, const AirField& field, int x, int y, int z) {
  if (rock.material[rock.layout.index(x, y, z)] != Material::Rock) return false;
  return field.isAir(x - 1, y, z) || field.isAir(x + 1, y, z) || field.isAir(x, y - 1, z) || field.isAir(x, y + 1, z) ||
         field.isAir(x, y, z - 1) || field.isAir(x, y, z + 1);
}

// A set of cells (sorted by index) defined by a predicate, kept current from
// the cells that change instead of rescanning the grid.
template <typename Predicate>
class TrackedCells {
 public:
  TrackedCells(const GridLayout& g, Predicate member) : g_(g), member_(std::move(member)), flag_(g.cellCount(), 0) {
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x)
          if (member_(x, y, z)) {
            const Cell c = Cell(g.index(x, y, z));
            flag_[c] = 1;
            cells_.push_back(c);
          }
  }

  const std::vector<Cell>& cells() const { return cells_; }

  // Re-evaluates the changed cells and, when `with_neighbours`, their face
  // neighbours. A cell listed twice is harmless: its flag already agrees.
  void update(const std::vector<Cell>& changed, bool with_neighbours) {
    std::vector<Cell> added;
    bool any_removed = false;
    const auto reevaluate = [&](Cell c, const VoxelCoord& p) {
      const std::uint8_t now = member_(p.x, p.y, p.z) ? 1 : 0;
      if (now == flag_[c]) return;
      flag_[c] = now;
      if (now)
        added.push_back(c);
      else
        any_removed = true;
    };
    for (Cell c : changed) {
      const VoxelCoord p = g_.coord(c);
      reevaluate(c, p);
      if (!with_neighbours) continue;
      for (const auto& o : kFaceNeighbours)
        if (g_.contains(p.x + o[0], p.y + o[1], p.z + o[2]))
          reevaluate(Cell(g_.index(p.x + o[0], p.y + o[1], p.z + o[2])), {p.x + o[0], p.y + o[1], p.z + o[2]});
    }
    std::sort(added.begin(), added.end());
    if (any_removed) std::erase_if(cells_, [this](Cell c) { return !flag_[c]; });
    if (!added.empty()) {
      const std::size_t old_size = cells_.size();
      cells_.insert(cells_.end(), added.begin(), added.end());
      std::inplace_merge(cells_.begin(), cells_.begin() + std::ptrdiff_t(old_size), cells_.end());
    }
  }

 private:
  GridLayout g_;
  Predicate member_;
  std::vector<std::uint8_t> flag_;
  std::vector<Cell> cells_;
};

}  // namespace

int plannedCycles(const SimParams& preset, double h) {
  if (preset.stop.cycles) return *preset.stop.cycles;
  // A whisker of tolerance so that time = 3 at h = 0.1 is 30 cycles, not 31.
  return std::max(1, int(std::ceil(preset.stop.time.value_or(0.0) / h - 1e-9)));
}

struct WeatheringSimulation::State {
  State(VoxelRock initial, SimParams p)
      : preset(std::move(p)),
        rock(std::move(initial)),
        estimators(buildEstimators(preset, rock.layout.h, reach)),
        field(rock, reach),
        graph(bindBubbleGraph(preset, rock.layout, field, estimators)),
        exposed(rock.layout, [this](int x, int y, int z) { return isExposed(rock, field, x, y, z); }),
        colluvium(
            rock.layout,
            [this](int x, int y, int z) { return rock.material[rock.layout.index(x, y, z)] == Material::Colluvium; }),
        rockfall(rock.layout),
        colluvium_model(rock.layout, preset.colluvium, preset.seed),
        geology(preset.durability, preset.grid.size, preset.seed),
        planned_cycles(plannedCycles(preset, rock.layout.h)),
        initial_rock(rock.count(Material::Rock)),
        rock_count(initial_rock) {}

  // Rockfall and colluvium need the ground to fall and pile onto (SPEC §2.1).
  bool rockfallOn() const { return rock.layout.ground && preset.rockfall.mode != RockfallMode::Off; }
  // Colluvium comes from decimated rock (yield) and from crumbled rockfall.
  bool colluviumOn() const {
    return rock.layout.ground && (preset.colluvium.yield > 0.0 || preset.rockfall.mode == RockfallMode::Crumble);
  }

  using CellPredicate = std::function<bool(int, int, int)>;

  const SimParams preset;  // a copy: the simulation owns its parameters
  VoxelRock rock;
  int reach = 1;
  std::vector<BubbleEstimator> estimators;
  AirField field;
  BubbleGraph graph;
  TrackedCells<CellPredicate> exposed;    // rock with a face on air
  TrackedCells<CellPredicate> colluvium;  // every colluvium voxel
  RockfallSolver rockfall;
  ColluviumModel colluvium_model;
  Geology geology;  // the rock's structure, which every keyframe's graph is read through
  int planned_cycles;
  int cycle = 0;
  std::size_t initial_rock, rock_count;
  std::size_t next_keyframe = 0;
  std::vector<std::uint8_t> decimate;  // per exposed voxel, this cycle
};

WeatheringSimulation::WeatheringSimulation(VoxelRock rock, SimParams params)
    : state_(std::make_unique<State>(std::move(rock), std::move(params))) {}
WeatheringSimulation::~WeatheringSimulation() = default;

const VoxelRock& WeatheringSimulation::rock() const {
  return state_->rock;
}
double WeatheringSimulation::pendingColluvium() const {
  return state_->colluvium_model.pendingUnits();
}
VoxelRock WeatheringSimulation::release() {
  return std::move(state_->rock);
}

bool WeatheringSimulation::finished() const {
  const State& st = *state_;
  if (st.cycle >= st.planned_cycles) return true;
  const auto& fraction = st.preset.stop.rock_volume_fraction;
  return st.cycle > 0 && fraction && double(st.rock_count) <= *fraction * double(st.initial_rock);
}

CycleStats WeatheringSimulation::step() {
  State& st = *state_;
  VoxelRock& rock = st.rock;
  const GridLayout& g = rock.layout;
  const SimParams& preset = st.preset;

  // Directability (SPEC §2.4): a keyframe whose time has come replaces the
  // graph for all rock still standing; integrities are kept.
  const auto& keyframes = preset.durability.keyframes;
  const double start_time = st.cycle * g.h;
  while (st.next_keyframe < keyframes.size() && keyframes[st.next_keyframe].at <= start_time + 1e-9 * g.h) {
    assignDurability(rock, DurabilityField(keyframes[st.next_keyframe].graph, preset.seed, st.next_keyframe + 1),
                     st.geology);
    ++st.next_keyframe;
  }

  using Clock = std::chrono::steady_clock;
  const auto secondsSince = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  auto phase_start = Clock::now();

  // Weathering: every exposure comes from the state at the cycle's start;
  // each task writes only its own voxels' integrity.
  const std::vector<Cell>& cells = st.exposed.cells();
  st.decimate.assign(cells.size(), 0);
  const BubbleGraph& graph = st.graph;
  const AirField& field = st.field;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Cell c = cells[i];
                        const VoxelCoord p = g.coord(c);
                        const std::size_t band = std::size_t(graph.band_of_layer[std::size_t(p.z)]);
                        const double s = exposureAt(field, graph.estimators[band], p.x, p.y, p.z);
                        const double w = graph.spheroidal[band] * applyResponse(preset.response, s) +
                                         graph.cavernous[band] * applyResponse(preset.response, 1.0 - s);
                        const float integrity = float(double(rock.integrity[c]) - w / double(rock.durability[c]));
                        rock.integrity[c] = integrity;
                        st.decimate[i] = integrity <= 0.f;
                      }
                    });

  // Decimation, all at once.
  std::vector<Cell> decimated;
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (st.decimate[i]) decimated.push_back(cells[i]);
  for (Cell c : decimated) {
    rock.material[c] = Material::Air;
    rock.durability[c] = 0.f;
  }
  CycleStats stats;
  stats.curvature_seconds = secondsSince(phase_start);
  stats.exposed = cells.size();
  stats.decimated = decimated.size();

  // Every cell whose material changes this cycle, and every cell that stops
  // being solid (what rockfall must check support around).
  std::vector<Cell> changed = decimated;
  std::vector<Cell> vacated = decimated;

  // Colluvium (SPEC §2.7): deposit, settle, carry some away, settle again.
  std::vector<Cell> unstable;
  phase_start = Clock::now();
  if (st.colluviumOn()) {
    // Colluvium that rested on, or leaned against, decimated rock may move.
    for (Cell c : decimated) {
      const VoxelCoord p = g.coord(c);
      for (int dz = 0; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (g.contains(p.x + dx, p.y + dy, p.z + dz) &&
                rock.material[g.index(p.x + dx, p.y + dy, p.z + dz)] == Material::Colluvium)
              unstable.push_back(Cell(g.index(p.x + dx, p.y + dy, p.z + dz)));
    }
    stats.deposited = st.colluvium_model.deposit(rock, decimated, changed, unstable);
    st.colluvium_model.settle(rock, unstable, changed, vacated);
    st.colluvium.update(changed, false);
    stats.removed = st.colluvium_model.remove(rock, st.colluvium.cells(), st.cycle + 1, changed, vacated, unstable);
    st.colluvium_model.settle(rock, unstable, changed, vacated);
  }

  // Rockfall (SPEC §2.6): until nothing floats. Crumbled rock settles as
  // colluvium, which can uncover more to fall.
  stats.colluvium_seconds = secondsSince(phase_start);
  phase_start = Clock::now();
  if (st.rockfallOn()) {
    for (bool first = true;; first = false) {
      RockfallOutcome fall = st.rockfall.apply(rock, preset.rockfall.mode, vacated, first && st.cycle == 0);
      vacated.clear();
      stats.fallen += fall.fallen;
      stats.crumbled += fall.crumbled;
      changed.insert(changed.end(), fall.changed.begin(), fall.changed.end());
      if (fall.fallen == 0 || fall.crumbled == 0 || !st.colluviumOn()) break;
      for (Cell c : fall.changed)
        if (rock.material[c] == Material::Colluvium) unstable.push_back(c);
      st.colluvium_model.settle(rock, unstable, changed, vacated);
      if (vacated.empty()) break;
    }
  }

  stats.rockfall_seconds = secondsSince(phase_start);

  // Bring the air bits and the tracked sets up to date from the changed cells.
  for (Cell c : changed) {
    const VoxelCoord p = g.coord(c);
    st.field.setAir(p.x, p.y, p.z, rock.material[c] == Material::Air);
  }
  st.exposed.update(changed, true);
  st.colluvium.update(changed, false);

  stats.cycle = ++st.cycle;
  stats.time = st.cycle * g.h;
  st.rock_count -= decimated.size() + stats.crumbled;
  stats.rock = st.rock_count;
  stats.colluvium = st.colluvium.cells().size();
  return stats;
}

WeatheringResult weatherRock(VoxelRock rock, const SimParams& preset, const CycleObserver& observe) {
  WeatheringSimulation simulation(std::move(rock), preset);
  WeatheringResult result;
  while (!simulation.finished()) {
    result.cycles.push_back(simulation.step());
    if (observe) observe(result.cycles.back());
  }
  result.rock = simulation.release();
  return result;
}

std::vector<float> exposureField(const VoxelRock& rock, const SimParams& preset) {
  const GridLayout& g = rock.layout;
  int reach = 1;
  const std::vector<BubbleEstimator> estimators = buildEstimators(preset, g.h, reach);
  const AirField field(rock, reach);
  const BubbleGraph graph = bindBubbleGraph(preset, g, field, estimators);
  std::vector<float> s(g.cellCount(), 0.f);
  tbb::parallel_for(0, g.nz, [&](int z) {
    const BoundEstimator& estimator = graph.estimators[std::size_t(graph.band_of_layer[std::size_t(z)])];
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (isExposed(rock, field, x, y, z)) s[g.index(x, y, z)] = float(exposureAt(field, estimator, x, y, z));
  });
  return s;
}

}  // namespace rockbake
