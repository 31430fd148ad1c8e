#include "sim/weathering.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sim/bubble.h"
#include "sim/colluvium.h"
#include "sim/curvature.h"
#include "sim/durability.h"
#include "sim/family.h"
#include "sim/grid_layout.h"
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

std::vector<BubbleEstimator> buildEstimators(const std::vector<BubbleBand>& bubbles, double h, int& reach) {
  std::vector<BubbleEstimator> estimators;
  reach = 1;  // exposure looks at face neighbours even for sub-voxel bubbles
  for (const auto& band : bubbles) {
    estimators.push_back(makeBubbleEstimator(band.bubble, h));
    reach = std::max(reach, estimators.back().reach);
  }
  return estimators;
}

BubbleGraph bindBubbleGraph(const std::vector<BubbleBand>& bubbles, const GridLayout& g, const AirField& field,
                            const std::vector<BubbleEstimator>& estimators) {
  BubbleGraph graph;
  for (std::size_t b = 0; b < bubbles.size(); ++b) {
    graph.estimators.push_back(bindEstimator(field, estimators[b]));
    graph.spheroidal.push_back(bubbles[b].spheroidal);
    graph.cavernous.push_back(bubbles[b].cavernous);
  }
  graph.band_of_layer.resize(std::size_t(g.nz));
  for (int z = 0; z < g.nz; ++z) {
    const double a = g.altitude(z);
    int band = int(bubbles.size()) - 1;  // above the domain: the top band
    for (int b = 0; b < int(bubbles.size()); ++b)
      if (a <= bubbles[std::size_t(b)].up_to) {
        band = b;
        break;
      }
    graph.band_of_layer[std::size_t(z)] = band;
  }
  return graph;
}

// docs/model.md §2: rock with at least one face neighbour of air.
bool isExposed(const VoxelRock& rock, const AirField& field, int x, int y, int z) {
  if (rock.material[rock.layout.index(x, y, z)] != Material::Rock) return false;
  return field.isAir(x - 1, y, z) || field.isAir(x + 1, y, z) || field.isAir(x, y - 1, z) || field.isAir(x, y + 1, z) ||
         field.isAir(x, y, z - 1) || field.isAir(x, y, z + 1);
}

// A set of cells (sorted by index) defined by a predicate, kept current from
// the cells that change instead of rescanning the grid. Membership is one bit
// per cell.
template <typename Predicate>
class TrackedCells {
 public:
  TrackedCells(const GridLayout& g, Predicate member)
      : g_(g), member_(std::move(member)), flag_((g.cellCount() + 63) / 64, 0) {
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x)
          if (member_(x, y, z)) {
            const Cell c = Cell(g.index(x, y, z));
            setFlag(c, true);
            cells_.push_back(c);
          }
  }

  const std::vector<Cell>& cells() const { return cells_; }

  // Re-evaluates the changed cells and, when `with_neighbours`, their face
  // neighbours. A cell listed twice is harmless: its flag already agrees.
  // `entered`, if given, receives the cells that joined the set, sorted.
  void update(const std::vector<Cell>& changed, bool with_neighbours, std::vector<Cell>* entered = nullptr) {
    Changes changes;
    const auto reevaluate = [&](Cell c, const VoxelCoord& p) { assign(c, member_(p.x, p.y, p.z), changes); };
    for (Cell c : changed) {
      const VoxelCoord p = g_.coord(c);
      reevaluate(c, p);
      if (!with_neighbours) continue;
      for (const auto& o : kFaceNeighbours)
        if (g_.contains(p.x + o[0], p.y + o[1], p.z + o[2]))
          reevaluate(Cell(g_.index(p.x + o[0], p.y + o[1], p.z + o[2])), {p.x + o[0], p.y + o[1], p.z + o[2]});
    }
    merge(changes, entered);
  }

  // update(changed, true) for the rock under colluvium, testing only where membership may have
  // changed: a changed cell is re-tested; a neighbour that is a member is re-tested (it may have
  // lost its only colluvium neighbour); a neighbour that is not joins, untested, when
  // `joins(changed cell, neighbour)` (rock next to what is colluvium now); no other neighbour can
  // have changed. The same set as update(changed, true).
  template <typename Joins>
  void updateAroundChanges(const std::vector<Cell>& changed, Joins joins) {
    Changes changes;
    const auto set = [&](Cell c, bool now) { assign(c, now, changes); };
    const std::ptrdiff_t sx = 1, sy = g_.nx, sz = std::ptrdiff_t(g_.nx) * g_.ny;
    const auto nx = std::uint32_t(g_.nx), ny = std::uint32_t(g_.ny);
    for (Cell c : changed) {
      // coord() in 32-bit arithmetic (a Cell is 32 bits): this loop runs on every changed cell each cycle.
      const std::uint32_t row = c / nx, z = row / ny;
      const VoxelCoord p{int(c - row * nx), int(row - z * ny), int(z)};
      set(c, member_(p.x, p.y, p.z));
      const std::ptrdiff_t step[6] = {-sx, sx, -sy, sy, -sz, sz};
      const bool inside[6] = {p.x > 0, p.x + 1 < g_.nx, p.y > 0, p.y + 1 < g_.ny, p.z > 0, p.z + 1 < g_.nz};
      for (int i = 0; i < 6; ++i) {
        if (!inside[i]) continue;
        const Cell n = Cell(std::ptrdiff_t(c) + step[i]);
        if (flag(n)) {
          set(n, member_(p.x + kFaceNeighbours[i][0], p.y + kFaceNeighbours[i][1], p.z + kFaceNeighbours[i][2]));
        } else if (joins(c, n)) {
          set(n, true);
        }
      }
    }
    merge(changes, nullptr);
  }

 private:
  // An update's changes: the cells that joined, and whether any left.
  struct Changes {
    std::vector<Cell> added;
    bool any_removed = false;
  };
  // Sets c's membership to `now`, noting the change.
  void assign(Cell c, bool now, Changes& changes) {
    if (now == flag(c)) return;
    setFlag(c, now);
    if (now)
      changes.added.push_back(c);
    else
      changes.any_removed = true;
  }
  // The changes into the sorted list; `entered`, if given, receives the cells that joined, sorted.
  void merge(Changes& changes, std::vector<Cell>* entered) {
    std::vector<Cell>& added = changes.added;
    std::sort(added.begin(), added.end());
    if (entered) *entered = added;
    if (changes.any_removed) std::erase_if(cells_, [this](Cell c) { return !flag(c); });
    if (!added.empty()) {
      const std::size_t old_size = cells_.size();
      cells_.insert(cells_.end(), added.begin(), added.end());
      std::inplace_merge(cells_.begin(), cells_.begin() + std::ptrdiff_t(old_size), cells_.end());
    }
  }

  bool flag(Cell c) const { return (flag_[c >> 6] >> (c & 63)) & 1u; }
  void setFlag(Cell c, bool on) {
    const std::uint64_t bit = std::uint64_t(1) << (c & 63);
    flag_[c >> 6] = on ? (flag_[c >> 6] | bit) : (flag_[c >> 6] & ~bit);
  }

  GridLayout g_;
  Predicate member_;
  std::vector<std::uint64_t> flag_;
  std::vector<Cell> cells_;
};

struct ExposedRock {
  const VoxelRock* rock;
  const AirField* field;
  bool operator()(int x, int y, int z) const { return isExposed(*rock, *field, x, y, z); }
};
// Rock under colluvium: rock with a face on colluvium (docs/model.md §14).
struct CoveredRock {
  const VoxelRock* rock;
  bool operator()(int x, int y, int z) const {
    const GridLayout& g = rock->layout;
    if (rock->material[g.index(x, y, z)] != Material::Rock) return false;
    for (const auto& o : kFaceNeighbours)
      if (g.contains(x + o[0], y + o[1], z + o[2]) &&
          rock->material[g.index(x + o[0], y + o[1], z + o[2])] == Material::Colluvium)
        return true;
    return false;
  }
};
struct ColluviumCell {
  const VoxelRock* rock;
  bool operator()(int x, int y, int z) const {
    return rock->material[rock->layout.index(x, y, z)] == Material::Colluvium;
  }
};

// Runs body(cell) over sorted `cells` in parallel, in chunks that never split an x-row of `nx`
// cells, so that RowSpans writes from different chunks touch different rows (core/voxel_rock.h).
template <typename Body>
void forCellsByRow(const std::vector<Cell>& cells, int nx, Body body) {
  constexpr std::size_t kChunk = 1024;
  std::vector<std::size_t> bounds{0};
  for (std::size_t at = kChunk; at < cells.size(); at += kChunk) {
    const Cell row = cells[at - 1] / Cell(nx);
    while (at < cells.size() && cells[at] / Cell(nx) == row) ++at;
    if (at == cells.size()) break;
    bounds.push_back(at);
  }
  bounds.push_back(cells.size());
  tbb::parallel_for(std::size_t(0), bounds.size() - 1, [&](std::size_t i) {
    for (std::size_t j = bounds[i]; j < bounds[i + 1]; ++j) body(cells[j]);
  });
}

// The cells one cycle touches, gathered as its phases run.
struct CycleCells {
  std::vector<Cell> changed;   // every cell whose material changed this cycle
  std::vector<Cell> vacated;   // cells that stopped being solid: rockfall checks support around them
  std::vector<Cell> unstable;  // colluvium out of rest, for settling
  std::vector<Cell> fell;      // every cell rockfall emptied or filled
};

}  // namespace

int plannedCycles(const SimParams& preset, double h) {
  if (preset.stop.cycles) return *preset.stop.cycles;
  // A whisker of tolerance so that time = 3 at h = 0.1 is 30 cycles, not 31.
  return std::max(1, int(std::ceil(preset.stop.time.value_or(0.0) / h - 1e-9)));
}

// The widest reach of any keyframe's bubbles, so the air field is built wide
// enough once (it is widened later only if keyframes are replaced).
static int keyframeReach(const SimParams& params, double h) {
  int reach = 1;
  for (const auto& k : params.durability.keyframes)
    if (k.bubbles) {
      int r = 1;
      buildEstimators(*k.bubbles, h, r);
      reach = std::max(reach, r);
    }
  return reach;
}

struct WeatheringSimulation::State {
  State(VoxelRock initial, SimParams p)
      : preset(std::move(p)),
        rock(std::move(initial)),
        bubbles(preset.bubbles),
        response(preset.response),
        estimators(buildEstimators(bubbles, rock.layout.h, reach)),
        field(rock, std::max(reach, keyframeReach(preset, rock.layout.h))),
        graph(bindBubbleGraph(bubbles, rock.layout, field, estimators)),
        exposed(rock.layout, ExposedRock{&rock, &field}),
        covered(rock.layout, CoveredRock{&rock}),
        colluvium_count(rock.count(Material::Colluvium)),
        rockfall(rock.layout),
        colluvium_model(rock.layout, preset.colluvium, preset.seed),
        geology(individualDurability(preset), simulationDomain(preset), preset.seed),
        planned_cycles(plannedCycles(preset, rock.layout.h)),
        initial_rock(rock.count(Material::Rock)),
        rock_count(initial_rock) {
    if (preset.colluvium.removal > 0.0) colluvium.emplace(rock.layout, ColluviumCell{&rock});
    // A fresh run (or a snapshot without history) starts its record: the blockout's surface is cycle 0.
    if (rock.history.empty()) {
      rock.history = VoxelHistory(rock.layout);
      recordHistory({}, {}, 0);
    }
  }

  // Rockfall and colluvium need the ground to fall and pile onto (docs/model.md §1).
  bool rockfallOn() const { return rock.layout.ground && preset.rockfall.mode != RockfallMode::Off; }
  // Colluvium comes from decimated rock (yield) and from crumbled rockfall.
  bool colluviumOn() const {
    return rock.layout.ground && (preset.colluvium.yield > 0.0 || preset.rockfall.mode == RockfallMode::Crumble);
  }

  // A keyframe's bubble graph takes over: the estimators are rebuilt and
  // re-bound, the air field widened first if they reach past its apron.
  void useBubbles(const std::vector<BubbleBand>& next) {
    bubbles = next;
    estimators = buildEstimators(bubbles, rock.layout.h, reach);
    if (reach > field.apron()) field = AirField(rock, reach);
    graph = bindBubbleGraph(bubbles, rock.layout, field, estimators);
  }

  // Directability (docs/model.md §4): every keyframe whose time has come by
  // `time` replaces the durability graph for all rock still standing
  // (integrities are kept), and the bubble graph and response it carries.
  // `durability` false when resuming: the durability is already in the rock.
  void reachKeyframes(double time, bool durability) {
    const auto& keyframes = preset.durability.keyframes;
    const double h = rock.layout.h;
    while (next_keyframe < keyframes.size() && keyframes[next_keyframe].at <= time + 1e-9 * h) {
      const DurabilityKeyframe& k = keyframes[next_keyframe];
      if (k.graph && durability)
        assignDurability(rock, DurabilityField(*k.graph, preset.seed, next_keyframe + 1), geology);
      if (k.bubbles) useBubbles(*k.bubbles);
      if (k.response) response = *k.response;
      ++next_keyframe;
    }
  }

  // The phases of one cycle, in the order step() runs them.
  void weatherExposed();
  std::vector<Cell> decimateWeathered();
  void moveColluvium(const std::vector<Cell>& decimated, CycleCells& touched, CycleStats& stats);
  void fallUntilSupported(CycleCells& touched, CycleStats& stats);
  void updateTracking(const std::vector<Cell>& changed, std::vector<Cell>& newly_exposed);
  void recordHistory(const std::vector<Cell>& changed, const std::vector<Cell>& fell, int at_cycle);

  SimParams preset;  // a copy: the simulation owns its parameters
  VoxelRock rock;
  std::vector<BubbleBand> bubbles;  // in effect: the preset's, or the latest keyframe's
  ResponseParams response;          // likewise
  int reach = 1;
  std::vector<BubbleEstimator> estimators;
  AirField field;
  BubbleGraph graph;
  TrackedCells<ExposedRock> exposed;  // rock with a face on air
  TrackedCells<CoveredRock> covered;  // rock with a face on colluvium
  std::vector<Cell> newly_exposed;    // cells that joined `exposed` this cycle
  // Every colluvium voxel, in cell order: only removal needs the list, so it
  // is kept only when removal is on; the count is kept always.
  std::optional<TrackedCells<ColluviumCell>> colluvium;
  std::size_t colluvium_count;
  RockfallSolver rockfall;
  ColluviumModel colluvium_model;
  Geology geology;  // the rock's structure, which every keyframe's graph is read through
  int planned_cycles;
  int cycle = 0;
  std::size_t initial_rock, rock_count;
  std::size_t next_keyframe = 0;
  std::vector<std::uint8_t> decimate;  // per exposed voxel, this cycle
};

WeatheringSimulation::WeatheringSimulation(VoxelRock rock, SimParams params) {
  requireSimulationCells(rock.layout);
  state_ = std::make_unique<State>(std::move(rock), std::move(params));
}

WeatheringSimulation::WeatheringSimulation(SimulationSnapshot snapshot, SimParams params) {
  const GridLayout& g = snapshot.rock.layout;
  requireSimulationCells(g);
  const auto fits = [&](const RowSpans& spans) {
    const std::size_t rows = std::size_t(g.ny) * std::size_t(g.nz);
    return spans.nx == g.nx && spans.first.size() == rows && spans.values.size() == rows;
  };
  const auto historyFits = [&] {
    const auto grids = std::as_const(snapshot.rock.history).grids();
    return std::all_of(grids.begin(), grids.end(), [&](const RowSpans* spans) { return fits(*spans); });
  };
  if (snapshot.cycle < 0 || snapshot.rock.material.size() != g.cellCount() || !fits(snapshot.rock.integrity) ||
      !fits(snapshot.rock.durability) || (!snapshot.rock.history.empty() && !historyFits()) ||
      (!snapshot.rock.rind.empty() && snapshot.rock.rind.size() != g.cellCount()))
    throw std::invalid_argument("simulation snapshot: its grids do not match its layout");
  const int cycle = snapshot.cycle;
  state_ = std::make_unique<State>(std::move(snapshot.rock), std::move(params));
  State& st = *state_;
  st.colluvium_model.setAccumulators(std::move(snapshot.colluvium_columns));
  st.cycle = cycle;
  st.initial_rock = snapshot.initial_rock;
  st.rock_count = st.rock.count(Material::Rock);
  // The keyframes the cycles already run have reached (the last one ran at time (cycle - 1) h).
  if (cycle > 0) st.reachKeyframes((cycle - 1) * st.rock.layout.h, false);
}

WeatheringSimulation::~WeatheringSimulation() = default;

int WeatheringSimulation::cycle() const {
  return state_->cycle;
}

SimulationCounts WeatheringSimulation::counts() const {
  return {state_->rock_count, state_->exposed.cells().size(), state_->colluvium_count};
}

SimulationSnapshot WeatheringSimulation::snapshot() const {
  const State& st = *state_;
  return {st.rock, st.colluvium_model.accumulators(), st.cycle, st.initial_rock};
}

const SimParams& WeatheringSimulation::params() const {
  return state_->preset;
}

SimParams WeatheringSimulation::activeParams() const {
  SimParams active = state_->preset;
  active.bubbles = state_->bubbles;
  active.response = state_->response;
  return active;
}

void WeatheringSimulation::setKeyframes(std::vector<DurabilityKeyframe> keyframes) {
  State& st = *state_;
  const auto& reached = st.preset.durability.keyframes;
  if (keyframes.size() < st.next_keyframe)
    throw std::invalid_argument("setKeyframes: " + std::to_string(st.next_keyframe) +
                                " keyframes were already reached; they must be kept");
  for (std::size_t i = 0; i < st.next_keyframe; ++i)
    if (keyframes[i].at != reached[i].at)
      throw std::invalid_argument("setKeyframes: keyframe " + std::to_string(i) +
                                  " was already reached; it must be kept");
  for (std::size_t i = 1; i < keyframes.size(); ++i)
    if (keyframes[i].at < keyframes[i - 1].at)
      throw std::invalid_argument("setKeyframes: keyframes must be in time order");
  st.preset.durability.keyframes = std::move(keyframes);
}

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

// Weathering: every exposure comes from the state at the cycle's start;
// each task writes only its own voxels' integrity. Voxels of one x-row up
// to 7 apart are counted together (AirField::countAirRun).
void WeatheringSimulation::State::weatherExposed() {
  const GridLayout& g = rock.layout;
  const std::vector<Cell>& cells = exposed.cells();
  decimate.assign(cells.size(), 0);
  const std::size_t nx = std::size_t(g.nx);
  // Every exposed voxel gets its integrity slot before the parallel writes.
  for (Cell c : cells)
    if (!rock.integrity.covers(c / nx, int(c % nx))) rock.integrity.cover(c / nx, int(c % nx), int(c % nx));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::uint8_t dx[AirField::kRunWidth];
                      double s[AirField::kRunWidth];
                      for (std::size_t i = range.begin(); i != range.end();) {
                        const Cell c0 = cells[i];
                        const VoxelCoord p = g.coord(c0);
                        int n = 1;
                        dx[0] = 0;
                        while (n < AirField::kRunWidth && i + std::size_t(n) < range.end() &&
                               cells[i + std::size_t(n)] - c0 < Cell(AirField::kRunWidth) &&
                               p.x + int(cells[i + std::size_t(n)] - c0) < g.nx) {
                          dx[n] = std::uint8_t(cells[i + std::size_t(n)] - c0);
                          ++n;
                        }
                        const std::size_t band = std::size_t(graph.band_of_layer[std::size_t(p.z)]);
                        exposureRun(field, graph.estimators[band], p.x, p.y, p.z, dx, n, s);
                        const std::size_t row = c0 / nx;
                        for (int k = 0; k < n; ++k) {
                          const int x = p.x + dx[k];
                          const double w = graph.spheroidal[band] * applyResponse(response, s[k]) +
                                           graph.cavernous[band] * applyResponse(response, 1.0 - s[k]);
                          float& slot = rock.integrity.slot(row, x);
                          const float integrity = float(double(slot) - w / double(rock.durability.at(row, x)));
                          slot = integrity;
                          decimate[i + std::size_t(k)] = integrity <= 0.f;
                        }
                        i += std::size_t(n);
                      }
                    });
}

// Decimation, all at once: the voxels weathering brought to 0 become air.
std::vector<Cell> WeatheringSimulation::State::decimateWeathered() {
  const std::vector<Cell>& cells = exposed.cells();
  std::vector<Cell> decimated;
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (decimate[i]) decimated.push_back(cells[i]);
  for (Cell c : decimated) {
    rock.material[c] = Material::Air;
    rock.durability.set(c, 0.f);
  }
  if (colluviumOn()) colluvium_model.noteChanged(rock, decimated);
  return decimated;
}

// Colluvium (docs/model.md §7): deposit, settle, carry some away, settle again.
void WeatheringSimulation::State::moveColluvium(const std::vector<Cell>& decimated, CycleCells& touched,
                                                CycleStats& stats) {
  // Colluvium that rested on, or leaned against, decimated rock may move.
  colluvium_model.disturbedBy(rock, decimated, touched.unstable);
  stats.deposited = colluvium_model.deposit(rock, decimated, touched.changed, touched.unstable);
  // Colluvium that slides off the grid's side counts as carried away.
  stats.removed += colluvium_model.settle(rock, touched.unstable, touched.changed, touched.vacated);
  if (colluvium) {
    colluvium->update(touched.changed, false);
    stats.removed +=
        colluvium_model.remove(rock, colluvium->cells(), cycle + 1, touched.changed, touched.vacated, touched.unstable);
  }
  stats.removed += colluvium_model.settle(rock, touched.unstable, touched.changed, touched.vacated);
}

// Rockfall (docs/model.md §6): until nothing floats. What fell and what it
// fell from can leave colluvium out of rest (crumbled rock, colluvium carried
// down with a piece, piles that leaned on it); it settles, which may uncover
// more to fall.
void WeatheringSimulation::State::fallUntilSupported(CycleCells& touched, CycleStats& stats) {
  for (bool first = true;; first = false) {
    RockfallOutcome fall = rockfall.apply(rock, preset.rockfall.mode, touched.vacated, first && cycle == 0);
    touched.vacated.clear();
    stats.fallen += fall.fallen;
    stats.crumbled += fall.crumbled;
    touched.changed.insert(touched.changed.end(), fall.changed.begin(), fall.changed.end());
    touched.fell.insert(touched.fell.end(), fall.changed.begin(), fall.changed.end());
    if (fall.fallen == 0 || !colluviumOn()) break;
    colluvium_model.noteChanged(rock, fall.changed);
    std::vector<Cell> emptied;
    for (Cell c : fall.changed) {
      if (rock.material[c] == Material::Colluvium) touched.unstable.push_back(c);
      if (rock.material[c] == Material::Air) emptied.push_back(c);
    }
    colluvium_model.disturbedBy(rock, emptied, touched.unstable);
    stats.removed += colluvium_model.settle(rock, touched.unstable, touched.changed, touched.vacated);
    if (touched.vacated.empty()) break;
  }
}

// Brings the air bits and the tracked sets up to date from the changed cells.
void WeatheringSimulation::State::updateTracking(const std::vector<Cell>& changed, std::vector<Cell>& entered) {
  for (Cell c : changed) {
    const VoxelCoord p = rock.layout.coord(c);
    field.setAir(p.x, p.y, p.z, rock.material[c] == Material::Air);
  }
  exposed.update(changed, true, &entered);
  if (colluvium) colluvium->update(changed, false);
}

// The history of the state after cycle `at_cycle` (docs/model.md §14), with the rock under
// colluvium brought up to date from the cells that changed: rock newly exposed to air
// (all exposed rock at cycle 0), rock under colluvium, and scars, the standing exposed rock within
// kScarReach voxels of a cell rockfall emptied. Each cell's record depends on that cell alone
// (the exposure and cover records are written in parallel by rows, the scars serially in cell
// order): the same at any thread count. Costs the cells that changed and the rock under colluvium.
void WeatheringSimulation::State::recordHistory(const std::vector<Cell>& changed, const std::vector<Cell>& fell,
                                                int at_cycle) {
  // Rock next to a cell that is colluvium now is under colluvium; nothing else joins from a neighbour.
  covered.updateAroundChanges(changed, [m = rock.material.data()](Cell now, Cell neighbour) {
    return m[now] == Material::Colluvium && m[neighbour] == Material::Rock;
  });
  const GridLayout& g = rock.layout;
  VoxelHistory& hist = rock.history;
  hist.cycles = at_cycle;
  const float k = float(at_cycle);
  forCellsByRow(at_cycle == 0 ? exposed.cells() : newly_exposed, g.nx, [&](Cell c) {
    if (hist.exposed[c] < 0.f) hist.exposed.set(c, k);
  });
  forCellsByRow(covered.cells(), g.nx, [&](Cell c) {
    hist.covered.set(c, k);
    hist.covered_for.set(c, hist.covered_for[c] + 1.f);
  });
  if (fell.empty()) return;
  constexpr int kScarReach = 2;
  std::vector<Cell> moved = fell;
  std::sort(moved.begin(), moved.end());
  moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
  const auto isMoved = [&](Cell c) { return std::binary_search(moved.begin(), moved.end(), c); };
  for (Cell c : moved) {
    if (rock.material[c] != Material::Air) continue;
    const VoxelCoord p = g.coord(c);
    for (int z = p.z - kScarReach; z <= p.z + kScarReach; ++z)
      for (int y = p.y - kScarReach; y <= p.y + kScarReach; ++y)
        for (int x = p.x - kScarReach; x <= p.x + kScarReach; ++x) {
          if (!g.contains(x, y, z)) continue;
          const Cell n = Cell(g.index(x, y, z));
          if (hist.scarred[n] != k && rock.material[n] == Material::Rock && isExposed(rock, field, x, y, z) &&
              !isMoved(n))
            hist.scarred.set(n, k);
        }
  }
}

CycleStats WeatheringSimulation::step() {
  State& st = *state_;
  const double h = st.rock.layout.h;

  st.reachKeyframes(st.cycle * h, true);

  using Clock = std::chrono::steady_clock;
  const auto secondsSince = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  auto phase_start = Clock::now();

  st.weatherExposed();
  const std::vector<Cell> decimated = st.decimateWeathered();
  CycleStats stats;
  stats.times.add("curvature", secondsSince(phase_start));
  stats.exposed = st.exposed.cells().size();
  stats.decimated = decimated.size();

  CycleCells touched{decimated, decimated, {}, {}};
  phase_start = Clock::now();
  const ColluviumModel::SettleWork settled_before = st.colluvium_model.settleWork();
  if (st.colluviumOn()) st.moveColluvium(decimated, touched, stats);
  stats.times.add("colluvium", secondsSince(phase_start));
  phase_start = Clock::now();
  if (st.rockfallOn()) st.fallUntilSupported(touched, stats);
  stats.times.add("rockfall", secondsSince(phase_start));
  const ColluviumModel::SettleWork& settled = st.colluvium_model.settleWork();
  stats.settle_work = settled.work - settled_before.work;
  stats.settle_largest_tiles = settled.largest_tiles - settled_before.largest_tiles;
  stats.settle_two_workers = settled.two_workers - settled_before.two_workers;

  st.updateTracking(touched.changed, st.newly_exposed);
  phase_start = Clock::now();
  st.recordHistory(touched.changed, touched.fell, st.cycle + 1);
  stats.times.add("history", secondsSince(phase_start));

  stats.cycle = ++st.cycle;
  stats.time = st.cycle * h;
  st.rock_count -= decimated.size() + stats.crumbled;
  stats.rock = st.rock_count;
  // Settling and falling move colluvium; only these make or unmake it.
  st.colluvium_count += stats.deposited + stats.crumbled - stats.removed;
  stats.colluvium = st.colluvium_count;
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

std::vector<float> exposureField(const VoxelRock& rock, const std::vector<BubbleBand>& bubbles) {
  const GridLayout& g = rock.layout;
  int reach = 1;
  const std::vector<BubbleEstimator> estimators = buildEstimators(bubbles, g.h, reach);
  const AirField field(rock, reach);
  const BubbleGraph graph = bindBubbleGraph(bubbles, g, field, estimators);
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
