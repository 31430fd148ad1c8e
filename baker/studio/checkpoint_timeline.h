// The studio's in-memory checkpoints (docs/studio.md, "Seeking"): snapshots of
// its simulation by cycle, so that a seek restores the latest one at or before
// its target and re-simulates from there. Bounded in count and in bytes, however
// far the timeline runs: a checkpoint is kept every `spacing` cycles, and when
// one more would pass either bound, the spacing doubles and every checkpoint off
// the new spacing goes (cycle 0's always stays). A seek then re-simulates fewer
// than `spacing` cycles, and the checkpoints hold at most max_bytes (cycle 0's
// alone when it is larger). Plain data; not thread-safe.
#pragma once

#include <cstddef>
#include <map>
#include <vector>

#include "sim/weathering.h"

namespace rockbake {

struct CheckpointBounds {
  std::size_t max_count = 32;
  std::size_t max_bytes = std::size_t(256) << 20;
};

// Bytes a snapshot holds (its arrays' capacities).
std::size_t snapshotBytes(const SimulationSnapshot& snapshot);

class CheckpointTimeline {
 public:
  explicit CheckpointTimeline(CheckpointBounds bounds = {}) : bounds_(bounds) {}

  // Only `start` (cycle 0's snapshot) is kept; checkpoints come every
  // `spacing` cycles (at least 1) from here on.
  void restart(SimulationSnapshot start, int spacing);
  // Whether a checkpoint at `cycle` would be kept (it is on the spacing, and not there yet).
  bool wants(int cycle) const;
  // Keeps it, thinning as above (which may drop it again).
  void keep(SimulationSnapshot snapshot);
  // The latest checkpoint at or before `cycle`; cycle 0's at least.
  const SimulationSnapshot& atOrBefore(int cycle) const;
  // Drops every checkpoint after `cycle` (they belong to a branch left behind).
  void dropAfter(int cycle);

  std::vector<int> cycles() const;
  std::size_t bytes() const { return bytes_; }
  int spacing() const { return spacing_; }

 private:
  struct Kept {
    SimulationSnapshot snapshot;
    std::size_t bytes;
  };
  void thin();

  CheckpointBounds bounds_;
  std::map<int, Kept> kept_;  // by cycle; 0 always present after restart()
  std::size_t bytes_ = 0;
  int spacing_ = 1;
};

}  // namespace rockbake
