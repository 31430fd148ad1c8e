#include "sim/colluvium.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <deque>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/hash.h"

namespace rockbake {
namespace {

inline bool isAir(const VoxelRock& rock, int x, int y, int z) {
  const GridLayout& g = rock.layout;
  if (z < 0) return !g.ground;
  if (!g.contains(x, y, z)) return true;
  return rock.material[g.index(x, y, z)] == Material::Air;
}

// The 8 neighbour columns, edges before corners so ties prefer the nearer.
constexpr int kColumns[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};

// The smallest whole drop (voxels) steeper than tan(talus) · distance.
int slidingDrop(double talus_slope, double distance) {
  return 1 + int(std::min(std::floor(talus_slope * distance), 1e6));
}

}  // namespace

ColluviumModel::ColluviumModel(const GridLayout& layout, const ColluviumParams& params, std::uint64_t seed)
    : layout_(layout),
      params_(params),
      seed_(seed),
      talus_slope_(std::tan(params.talus_angle * std::numbers::pi / 180.0)),
      edge_drop_(slidingDrop(talus_slope_, 1.0)),
      corner_drop_(slidingDrop(talus_slope_, std::numbers::sqrt2)),
      yield_units_(std::llround(params.yield * double(kUnit))),
      accumulator_(std::size_t(layout.nx) * std::size_t(layout.ny), 0) {}

void ColluviumModel::track(const VoxelRock& rock) {
  if (tracking_) return;
  const GridLayout& g = layout_;
  column_words_ = std::size_t(g.nz + 63) / 64;
  solid_.assign(std::size_t(g.nx) * std::size_t(g.ny) * column_words_, 0);
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] != Material::Air)
          column(std::size_t(x) + std::size_t(g.nx) * std::size_t(y))[z / 64] |= std::uint64_t(1) << (z % 64);
  tracking_ = true;
}

void ColluviumModel::setSolid(Cell c, bool solid) {
  const std::size_t plane = std::size_t(layout_.nx) * std::size_t(layout_.ny);
  const std::size_t z = c / plane;
  std::uint64_t& word = column(c % plane)[z / 64];
  const std::uint64_t bit = std::uint64_t(1) << (z % 64);
  word = solid ? (word | bit) : (word & ~bit);
}

void ColluviumModel::setMaterial(VoxelRock& rock, Cell c, Material m) {
  rock.material[c] = m;
  setSolid(c, m != Material::Air);
}

void ColluviumModel::noteChanged(const VoxelRock& rock, const std::vector<Cell>& cells) {
  if (!tracking_) return;  // made from the rock as it is on first use
  for (Cell c : cells) setSolid(c, rock.material[c] != Material::Air);
}

std::int64_t ColluviumModel::restingCell(int x, int y, int z) const {
  const GridLayout& g = layout_;
  const std::uint64_t* bits = column(std::size_t(x) + std::size_t(g.nx) * std::size_t(y));
  // From an occupied start (an earlier unit landed there) climb to the first
  // air: the lowest clear bit at or above z (the bits past nz are clear).
  std::size_t word = std::size_t(z) / 64;
  std::uint64_t air = ~bits[word] & (~std::uint64_t(0) << (z % 64));
  while (air == 0 && ++word < column_words_) air = ~bits[word];
  if (air == 0) return -1;
  z = int(word * 64) + std::countr_zero(air);
  if (z >= g.nz) return -1;
  // Then fall to the highest solid cell below it and rest on top of it.
  std::uint64_t below = z % 64 ? bits[word] & ((std::uint64_t(1) << (z % 64)) - 1) : 0;
  while (below == 0 && word > 0) below = bits[--word];
  if (below != 0) return std::int64_t(g.index(x, y, int(word * 64) + 63 - std::countl_zero(below) + 1));
  if (!g.ground) return -1;  // nothing to land on
  return std::int64_t(g.index(x, y, 0));
}

std::size_t ColluviumModel::deposit(VoxelRock& rock, const std::vector<Cell>& decimated, std::vector<Cell>& changed,
                                    std::vector<Cell>& unstable) {
  const GridLayout& g = layout_;
  track(rock);
  std::size_t created = 0;
  for (Cell c : decimated) {  // in cell order: deterministic
    const VoxelCoord p = g.coord(c);
    std::int64_t& acc = accumulator_[std::size_t(p.x) + std::size_t(g.nx) * std::size_t(p.y)];
    acc += yield_units_;
    while (acc >= kUnit) {
      const std::int64_t landing = restingCell(p.x, p.y, p.z);
      if (landing < 0) break;  // the unit waits in the accumulator
      acc -= kUnit;
      setMaterial(rock, Cell(landing), Material::Colluvium);
      rock.durability.set(std::size_t(landing), 0.f);
      changed.push_back(Cell(landing));
      unstable.push_back(Cell(landing));
      ++created;
    }
  }
  return created;
}

std::size_t ColluviumModel::remove(VoxelRock& rock, const std::vector<Cell>& colluvium_cells, int cycle,
                                   std::vector<Cell>& changed, std::vector<Cell>& vacated,
                                   std::vector<Cell>& unstable) {
  if (params_.removal <= 0.0) return 0;
  const GridLayout& g = layout_;
  track(rock);
  // Decide from the state before any removal, so the order does not matter.
  std::vector<Cell> carried;
  for (Cell c : colluvium_cells) {
    const VoxelCoord p = g.coord(c);
    const bool exposed = isAir(rock, p.x - 1, p.y, p.z) || isAir(rock, p.x + 1, p.y, p.z) ||
                         isAir(rock, p.x, p.y - 1, p.z) || isAir(rock, p.x, p.y + 1, p.z) ||
                         isAir(rock, p.x, p.y, p.z - 1) || isAir(rock, p.x, p.y, p.z + 1);
    if (exposed &&
        unitInterval(counterHash(seed_, purposeId("colluvium-removal"), std::uint64_t(cycle), c)) < params_.removal)
      carried.push_back(c);
  }
  for (Cell c : carried) {
    setMaterial(rock, c, Material::Air);
    changed.push_back(c);
    vacated.push_back(c);
  }
  disturbedBy(rock, carried, unstable);  // what rested on or leaned against them
  return carried.size();
}

template <typename Note>
void ColluviumModel::forEachDisturbed(const VoxelRock& rock, Cell emptied, Note note) const {
  const GridLayout& g = layout_;
  const std::size_t plane = std::size_t(g.nx) * std::size_t(g.ny);
  const auto solid = [](const std::uint64_t* bits, int z) { return (bits[z / 64] >> (z % 64)) & 1u; };
  const auto colluvium = [&](std::size_t c) {
    if (rock.material[c] == Material::Colluvium) note(Cell(c));
  };
  const VoxelCoord p = g.coord(emptied);
  const std::uint64_t* own = column(emptied % plane);
  if (p.z + 1 < g.nz && solid(own, p.z + 1)) colluvium(emptied + plane);  // rested on it: falls
  if (p.z > 0 && solid(own, p.z - 1)) colluvium(emptied - plane);         // covered by it: may slide
  // A voxel beside it can slide towards this column only where the cell
  // beside it here is air, and only if nothing covers it (a cover that
  // leaves too is an emptied cell of its own).
  int air_top = p.z;  // this column is air from p.z to air_top
  while (air_top - p.z < std::max(edge_drop_, corner_drop_) && air_top + 1 < g.nz && !solid(own, air_top + 1))
    ++air_top;
  for (const auto& col : kColumns) {
    const int x = p.x + col[0], y = p.y + col[1];
    if (x < 0 || y < 0 || x >= g.nx || y >= g.ny) continue;
    const std::uint64_t* bits = column(std::size_t(x) + std::size_t(g.nx) * std::size_t(y));
    const int top = std::min(air_top, p.z + (col[0] != 0 && col[1] != 0 ? corner_drop_ : edge_drop_));
    for (int z = p.z; z <= top; ++z)
      if (solid(bits, z) && (z + 1 == g.nz || !solid(bits, z + 1))) colluvium(g.index(x, y, z));
  }
}

void ColluviumModel::disturbedBy(const VoxelRock& rock, const std::vector<Cell>& emptied, std::vector<Cell>& unstable) {
  track(rock);
  for (Cell c : emptied) forEachDisturbed(rock, c, [&](Cell d) { unstable.push_back(d); });
}

void ColluviumModel::settle(VoxelRock& rock, std::vector<Cell>& unstable, std::vector<Cell>& changed,
                            std::vector<Cell>& vacated) {
  const GridLayout& g = layout_;
  track(rock);
  // Where the colluvium voxel at p goes next, or -1 when it is stable.
  const auto nextCell = [&](const VoxelCoord& p) -> std::int64_t {
    if (p.z > 0 && isAir(rock, p.x, p.y, p.z - 1)) return restingCell(p.x, p.y, p.z - 1);  // it falls
    if (!isAir(rock, p.x, p.y, p.z + 1)) return -1;                                        // covered: held in place
    // Top of a pile: slide to the neighbour column where it rests lowest, if
    // that drop is steeper than the talus angle allows.
    std::int64_t target = -1;
    int best_rest = p.z;
    for (const auto& col : kColumns) {
      const int x = p.x + col[0], y = p.y + col[1];
      if (!g.contains(x, y, p.z) || !isAir(rock, x, y, p.z)) continue;
      const std::int64_t rest = restingCell(x, y, p.z);
      if (rest < 0) continue;
      const int rest_z = g.coord(Cell(rest)).z;
      const double distance = (col[0] != 0 && col[1] != 0) ? std::numbers::sqrt2 : 1.0;
      if (double(p.z - rest_z) > talus_slope_ * distance && rest_z < best_rest) {
        best_rest = rest_z;
        target = rest;
      }
    }
    return target;
  };

  std::deque<Cell> queue(unstable.begin(), unstable.end());
  unstable.clear();
  while (!queue.empty()) {
    const Cell start = queue.front();
    queue.pop_front();
    if (rock.material[start] != Material::Colluvium) continue;
    // Follow the voxel down-slope to where it rests. The cells it passes
    // through are held only for this moment, so leaving them disturbs nothing.
    Cell at = start;
    for (std::int64_t next = nextCell(g.coord(at)); next >= 0; next = nextCell(g.coord(at))) {
      setMaterial(rock, Cell(next), Material::Colluvium);
      setMaterial(rock, at, Material::Air);
      at = Cell(next);
    }
    if (at == start) continue;
    changed.push_back(start);
    changed.push_back(at);
    vacated.push_back(start);
    // Leaving its starting place can unsettle what rested on it, what it
    // covered, and what stood beside it (disturbedBy()).
    forEachDisturbed(rock, start, [&](Cell d) { queue.push_back(d); });
  }
}

void ColluviumModel::setAccumulators(std::vector<std::int64_t> accumulators) {
  if (accumulators.size() != accumulator_.size())
    throw std::invalid_argument("colluvium accumulators: " + std::to_string(accumulators.size()) +
                                " columns for a grid of " + std::to_string(accumulator_.size()));
  accumulator_ = std::move(accumulators);
}

double ColluviumModel::pendingUnits() const {
  std::int64_t total = 0;
  for (std::int64_t a : accumulator_) total += a;
  return double(total) / double(kUnit);
}

}  // namespace rockbake
