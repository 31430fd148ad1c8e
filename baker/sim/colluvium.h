// Colluvium (docs/model.md §7): weathered rock piles up at the foot of the rock.
//
// Each decimated rock voxel adds `yield` units to its (x, y) column's
// accumulator (fixed point, so sums are exact); every whole unit becomes a
// COLLUVIUM voxel dropped from the decimated voxel straight down onto the
// first solid below. Settling is Musgrave et al.'s thermal weathering on
// voxels: a colluvium voxel with air above moves to the 8-neighbour column
// where it would rest lowest while that drop exceeds tan(talus_angle) ·
// distance (distance 1 or √2 voxels); one with air below falls. Removal
// carries away exposed colluvium voxels with probability `removal` per cycle,
// decided by a counter hash of (seed, cycle, cell).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

class ColluviumModel {
 public:
  using Cell = std::uint32_t;

  ColluviumModel(const GridLayout& layout, const ColluviumParams& params, std::uint64_t seed);

  // Records every cell whose material changed in `changed`, every cell that
  // stopped being solid in `vacated`, and colluvium that may be unstable in
  // `unstable` (feed it to settle()). Return the voxels created / removed.
  std::size_t deposit(VoxelRock& rock, const std::vector<Cell>& decimated, std::vector<Cell>& changed,
                      std::vector<Cell>& unstable);
  std::size_t remove(VoxelRock& rock, const std::vector<Cell>& colluvium_cells, int cycle, std::vector<Cell>& changed,
                     std::vector<Cell>& vacated, std::vector<Cell>& unstable);
  // Moves colluvium until every pile is stable; `unstable` is consumed.
  void settle(VoxelRock& rock, std::vector<Cell>& unstable, std::vector<Cell>& changed, std::vector<Cell>& vacated);
  // Appends to `unstable` the colluvium voxels that may have lost their rest
  // when `emptied` (cells that were solid and are air now) emptied: the voxel
  // above each, the one below, and those of the 8 neighbour columns from its
  // level up to as high as the talus angle lets a stable voxel stand.
  void disturbedBy(const VoxelRock& rock, const std::vector<Cell>& emptied, std::vector<Cell>& unstable);
  // The model keeps its own record of which cells are solid, made from the
  // rock on its first deposit, remove or settle. Every later change to
  // rock.material made elsewhere (decimation, rockfall) must be noted here
  // before the model is used again.
  void noteChanged(const VoxelRock& rock, const std::vector<Cell>& cells);

  // Fractional units waiting in the accumulators (for conservation checks).
  double pendingUnits() const;
  // The accumulators themselves, per (x, y) column (x fastest): part of a
  // simulation snapshot. setAccumulators requires nx * ny entries.
  const std::vector<std::int64_t>& accumulators() const { return accumulator_; }
  void setAccumulators(std::vector<std::int64_t> accumulators);

  static constexpr std::int64_t kUnit = std::int64_t(1) << 24;  // one voxel in accumulator units

 private:
  // The cell a unit dropped at (x, y) from height z comes to rest in, or -1.
  std::int64_t restingCell(int x, int y, int z) const;
  // Calls note(c) for each colluvium voxel that may have lost its rest when
  // the cell `emptied` emptied (see disturbedBy()).
  template <typename Note>
  void forEachDisturbed(const VoxelRock& rock, Cell emptied, Note note) const;
  void track(const VoxelRock& rock);  // builds solid_ on first use
  // The bits of column x + nx y, z upwards.
  std::uint64_t* column(std::size_t xy) { return solid_.data() + xy * column_words_; }
  const std::uint64_t* column(std::size_t xy) const { return solid_.data() + xy * column_words_; }
  void setSolid(Cell c, bool solid);
  // How the model changes the rock: the material and its record together.
  void setMaterial(VoxelRock& rock, Cell c, Material m);

  GridLayout layout_;
  ColluviumParams params_;
  std::uint64_t seed_;
  double talus_slope_;  // tan(talus_angle)
  // The smallest drop (voxels) that makes a voxel slide to an edge / corner
  // neighbour, and so also how high above an emptied cell a voxel beside it
  // can have stood at rest.
  int edge_drop_, corner_drop_;
  std::int64_t yield_units_;               // yield in accumulator units
  std::vector<std::int64_t> accumulator_;  // per (x, y) column
  // Solid (not air) cells, one bit per z in each (x, y) column: a unit's
  // fall down a column is a bit scan instead of a cache miss per cell.
  std::vector<std::uint64_t> solid_;  // [(x + nx y) column_words_ + z / 64]; bits past nz are 0
  std::size_t column_words_ = 0;
  bool tracking_ = false;
};

}  // namespace rockbake
