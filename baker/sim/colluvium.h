// Colluvium (docs/model.md §7): weathered rock piles up at the foot of the rock.
//
// Each decimated rock voxel adds `yield` units to its (x, y) column's
// accumulator (fixed point, so sums are exact); every whole unit becomes a
// COLLUVIUM voxel dropped from the decimated voxel straight down onto the
// first solid below. Settling is Musgrave et al.'s thermal weathering on
// voxels: a colluvium voxel with air below falls; one with air above moves to
// the 8-neighbour column where it would rest lowest while that drop exceeds
// tan(talus_angle) · distance (distance 1 or √2 voxels); a moving voxel is
// followed to rest before the next one moves. For that to run in parallel,
// the (x, y) plane is cut into square tiles of kSettleTile columns, coloured
// like a 2 × 2 checkerboard. Settling goes round the four colours, a phase
// each, until nothing moves; in a phase every tile of that colour settles
// the voxels in it on its own thread, in cell order, those its moves disturb
// queued behind. A voxel may go up to kSettleReach columns beyond its tile;
// one that gets that far stops there and goes on in the phase of the tile
// it reached. Tiles of one colour are a tile apart, so no tile reads a cell
// another one of its phase writes: the piles depend on the tiling, never on
// the thread count or on the order a phase's tiles are taken in. Removal carries away
// exposed colluvium voxels with probability `removal` per cycle, decided by
// a counter hash of (seed, cycle, cell).
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
  // Moves colluvium until every pile is stable. `unstable` (any order,
  // repeats and cells that are not colluvium allowed) must hold every
  // colluvium voxel that may not be at rest; it is consumed. Appends each
  // cell whose material it changed to `changed` once, and those of them left
  // empty to `vacated`. Parallel (TBB) over the tiles of each phase. On a grid with ground, a
  // voxel that would slide off the grid's side leaves it (the ground and the apron go on beyond):
  // returns how many did.
  std::size_t settle(VoxelRock& rock, std::vector<Cell>& unstable, std::vector<Cell>& changed,
                     std::vector<Cell>& vacated);
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
  // Settling tiles' side, and how many columns beyond its tile a voxel may
  // move while its tile settles. A tile reads and writes columns up to the
  // reach beyond it; two tiles of one colour are kSettleTile columns apart,
  // so what they touch never meets.
  static constexpr int kSettleTile = 32;
  static constexpr int kSettleReach = (kSettleTile - 1) / 2;
  static_assert(kSettleReach >= 1, "a voxel must be able to step out of its tile");

  // For tests: settle the tiles of each phase one after another, in an order
  // shuffled by `seed` (0, the default: all at once). The result must not change.
  void shuffleTiles(std::uint64_t seed) { shuffle_seed_ = seed; }

  // How much settling there was to share between threads, counted in voxels
  // taken up plus steps made (deterministic), summed over every settle()
  // since the model was made: all of it; the sum over phases of the largest
  // tile's (no thread count does better); and the sum over phases of the
  // larger of two workers' shares, tiles dealt largest first to the less
  // loaded. work / two_workers bounds what 2 threads can gain (bench/README.md).
  struct SettleWork {
    std::uint64_t work = 0, largest_tiles = 0, two_workers = 0;
  };
  const SettleWork& settleWork() const { return settle_work_; }

 private:
  // The cell a unit dropped at (x, y) from height z comes to rest in, or -1.
  std::int64_t restingCell(int x, int y, int z) const;
  // The height a unit comes to rest at in the column `bits` when its cell z
  // is air: on the highest solid cell below, or on the ground; -1 without one.
  int restingHeight(const std::uint64_t* bits, int z) const;
  // Moves p to where the colluvium voxel there steps next; false when it is
  // at rest. `lifted`, the cell its path set out from, counts as air.
  bool step(VoxelCoord& p, const VoxelCoord& lifted) const;
  // Calls note(c) for each colluvium voxel that may have lost its rest when
  // the cell `emptied` emptied (see disturbedBy()).
  template <typename Note>
  void forEachDisturbed(const VoxelRock& rock, Cell emptied, Note note) const;
  // Settling tiles: the tile of a cell's column (x fastest), and its colour.
  int tileOf(Cell c) const;
  int colourOf(int tile) const;
  // One phase: settles `cells` (all in tiles of one colour; any order,
  // repeats allowed) tile by tile; appends to `handed_on` the voxels outside
  // those tiles that may not be at rest, and each move's start and end to `moved`.
  // Returns how many voxels left the grid.
  std::size_t settlePhase(VoxelRock& rock, std::vector<Cell>& cells, std::vector<Cell>& handed_on,
                          std::vector<Cell>& moved);
  // Adds one phase's tiles' work to settle_work_.
  void noteWork(std::vector<std::uint64_t> tile_work);
  // Settles the voxels `cells` of tile (tx, ty); appends to `handed_on` the
  // voxels outside it that may not be at rest, and to `moved` each move.
  // Returns its work (voxels taken up plus steps made).
  // Adds to `left` the voxels that slid off the grid.
  std::uint64_t settleTile(VoxelRock& rock, int tx, int ty, std::vector<Cell> cells, std::vector<Cell>& handed_on,
                           std::vector<Cell>& moved, std::size_t& left);
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
  int tiles_x_;  // settling tiles along x
  std::uint64_t shuffle_seed_ = 0;
  SettleWork settle_work_;
};

}  // namespace rockbake
