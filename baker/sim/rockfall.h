// Rockfall (SPEC §2.6, after Ito et al. without slippage): solid material
// (rock ∪ colluvium) that is not 6-connected to the ground falls straight
// down, rigidly, whole voxels at a time, until one more step would overlap
// solid or the ground; repeated until nothing floats.
//
// Support is checked locally when it can be: if the solid cells around every
// cluster of removed cells are still connected to each other (and to the
// ground, where the cluster touched it), removing them cannot have cut
// anything loose, and no labelling is needed. Otherwise the grid is labelled
// by runs of solid cells along x (found per layer in parallel, joined with
// union-find): cost grows with the number of runs, not voxels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

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

  GridLayout layout_;
  std::vector<std::uint32_t> stamp_;  // per cell: the search that last visited it
  std::uint32_t current_stamp_ = 0;
  std::vector<std::uint8_t> state_;  // per cell, during the local test: 1 removed, 2 clustered
  std::size_t local_budget_;         // cells; by default about what labelling by runs costs
};

}  // namespace rockbake
