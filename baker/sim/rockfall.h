// Rockfall (docs/model.md §6, after Ito et al. without slippage): solid material
// (rock ∪ colluvium) that is not 6-connected to the ground falls straight
// down, rigidly, whole voxels at a time, until one more step would overlap
// solid or the ground; repeated until nothing floats.
//
// Support is checked locally when it can be: if the solid cells around every
// cluster of removed cells are still connected to each other (and to the
// ground, where the cluster touched it), removing them cannot have cut
// anything loose, and no labelling is needed. Otherwise the grid is labelled
// by runs of solid cells along x (found per layer in parallel, joined with
// union-find): cost grows with the number of runs, not voxels. Both run on
// all threads and give the same answer on any number.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

struct RockfallOutcome {
  std::size_t fallen = 0;              // voxels that moved
  std::size_t crumbled = 0;            // of those, rock turned into colluvium
  std::vector<std::uint32_t> changed;  // cells whose material changed (left or landed on)
  bool labelled = false;               // the whole grid was labelled this time
};

class RockfallSolver {
 public:
  explicit RockfallSolver(const GridLayout& layout);

  // `removed_solid`: cells that were solid before and are air now, since the
  // last call (sorted or not). `label_everything` skips the local test (the
  // first call of a simulation must, since nothing is known yet). Requires
  // layout.ground; Drop keeps fallen rock as rock, Crumble turns it into
  // colluvium (fallen colluvium stays colluvium either way).
  RockfallOutcome apply(VoxelRock& rock, RockfallMode mode, std::vector<std::uint32_t> removed_solid,
                        bool label_everything);

  // Local-test cell budget per call before falling back to labelling.
  void setLocalBudget(std::size_t cells) { local_budget_ = cells; }

 private:
  bool removalKeepsSupport(const VoxelRock& rock, const std::vector<std::uint32_t>& removed);
  std::vector<std::uint32_t> floatingCells(const VoxelRock& rock) const;

  // One bit per cell; every plane is all clear between calls.
  struct BitPlane {
    std::vector<std::uint64_t> words;
    bool test(std::uint32_t c) const { return (words[c >> 6] >> (c & 63)) & 1u; }
    void set(std::uint32_t c) { words[c >> 6] |= std::uint64_t(1) << (c & 63); }
    void clear(std::uint32_t c) { words[c >> 6] &= ~(std::uint64_t(1) << (c & 63)); }
  };

  // Per worker thread: the cells one search of the local test has visited.
  struct Scratch {
    BitPlane visited;  // cleared from the queue after each search
    std::vector<std::uint32_t> queue;
  };

  GridLayout layout_;
  tbb::enumerable_thread_specific<Scratch> scratch_;
  BitPlane removed_;          // during the local test: the removed cells
  BitPlane clustered_;        // during the local test: removed cells already put in a cluster
  BitPlane in_piece_;         // while a piece's drop is measured
  std::size_t local_budget_;  // cells; by default about what labelling by runs costs
};

}  // namespace rockbake
