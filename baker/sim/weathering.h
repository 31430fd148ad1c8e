// The simulation stage: takes the initial rock and SimParams, gives the
// weathered rock and per-cycle statistics; no I/O.
//
// The weathering cycles (docs/model.md §5–§9): each cycle estimates the exposure
// of every exposed rock voxel from the state at the cycle's start, lowers its
// integrity by w / D, and decimates all voxels whose integrity reached 0
// together; then colluvium is deposited, settled and carried away, and
// whatever no longer touches the ground falls. The result does not depend on
// the thread count.
//
// Cost per cycle grows with the number of exposed voxels, not the grid: the
// exposed set and the air bit field are updated from the cells that changed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "core/voxel_rock.h"
#include "platform/phase_times.h"
#include "preset/preset.h"

namespace rockbake {

struct CycleStats {
  int cycle = 0;              // 1-based
  double time = 0.0;          // simulation time at the cycle's end (world units)
  std::size_t rock = 0;       // rock voxels after the cycle
  std::size_t exposed = 0;    // rock voxels that weathered in this cycle
  std::size_t decimated = 0;  // rock voxels turned to air
  std::size_t colluvium = 0;  // colluvium voxels after the cycle
  std::size_t fallen = 0;     // voxels moved by rockfall
  std::size_t removed = 0;    // colluvium voxels carried away
  std::size_t deposited = 0;  // colluvium voxels created from decimated rock
  std::size_t crumbled = 0;   // fallen rock voxels turned into colluvium
  // Colluvium settling's work this cycle, and the parts of it that bound
  // what threads can share (ColluviumModel::SettleWork; for benchmarks).
  std::uint64_t settle_work = 0, settle_largest_tiles = 0, settle_two_workers = 0;
  // Wall-clock seconds of the cycle's phases, "curvature", "colluvium", "rockfall" and "history" (for
  // profiles; not deterministic).
  PhaseTimes times;
};

struct WeatheringResult {
  VoxelRock rock;
  std::vector<CycleStats> cycles;
};

// The whole state of a simulation between two cycles: what a checkpoint
// holds. A WeatheringSimulation made from it with the same SimParams runs on
// exactly as the one it was taken from (the keyframes reached are replayed
// from the parameters; their durability is already in the rock).
struct SimulationSnapshot {
  VoxelRock rock;                               // materials, integrity, durability
  std::vector<std::int64_t> colluvium_columns;  // colluvium accumulators, per (x, y) column
  int cycle = 0;                                // cycles run
  std::size_t initial_rock = 0;                 // rock voxels before the first cycle (for `until`)
};

struct SimulationCounts {
  std::size_t rock = 0;       // rock voxels
  std::size_t exposed = 0;    // rock voxels with a face on air (what the next cycle weathers)
  std::size_t colluvium = 0;  // colluvium voxels
};

// Number of cycles a preset asks for at voxel size h: cycles, or ceil(time / h).
int plannedCycles(const SimParams& preset, double h);

// One simulation, cycle by cycle: for callers that watch or time single
// cycles. Setup (bit field, exposed set) is done once in the constructor.
class WeatheringSimulation {
 public:
  // Both throw std::invalid_argument for a grid over kMaxSimulationCells (sim/grid_layout.h).
  WeatheringSimulation(VoxelRock rock, SimParams params);
  // Resumes a snapshot. Throws std::invalid_argument if it does not fit the parameters' grid.
  WeatheringSimulation(SimulationSnapshot snapshot, SimParams params);
  ~WeatheringSimulation();
  WeatheringSimulation(const WeatheringSimulation&) = delete;
  WeatheringSimulation& operator=(const WeatheringSimulation&) = delete;

  CycleStats step();      // runs the next cycle
  bool finished() const;  // planned cycles done, or `until` reached
  const VoxelRock& rock() const;
  double pendingColluvium() const;  // fractional units waiting in the accumulators
  VoxelRock release();              // the rock; the simulation is spent

  int cycle() const;  // cycles run so far
  SimulationCounts counts() const;
  SimulationSnapshot snapshot() const;
  const SimParams& params() const;
  // The parameters in effect now: the bubble graph and response of the
  // latest keyframe reached (for attributes computed from the current state).
  SimParams activeParams() const;
  // Replaces the keyframes (directability while running, docs/studio.md). Keyframes
  // the simulation has already reached must stay as they are, at the same
  // index: throws std::invalid_argument otherwise.
  void setKeyframes(std::vector<DurabilityKeyframe> keyframes);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

using CycleObserver = std::function<void(const CycleStats&)>;

WeatheringResult weatherRock(VoxelRock rock, const SimParams& preset, const CycleObserver& observe = {});

// Calibrated exposure s of every voxel of `rock` (0 where not exposed rock),
// using the preset's bubble graph: the curvature attribute later stages bake.
std::vector<float> exposureField(const VoxelRock& rock, const std::vector<BubbleBand>& bubbles);

}  // namespace rockbake
