#include "sim/colluvium.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "core/hash.h"

namespace rockbake {
namespace {

bool isAir(const VoxelRock& rock, int x, int y, int z) {
  const GridLayout& g = rock.layout;
  if (z < 0) return !g.ground;
  if (!g.contains(x, y, z)) return true;
  return rock.material[g.index(x, y, z)] == Material::Air;
}

// The 8 neighbour columns, edges before corners so ties prefer the nearer.
constexpr int kColumns[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};

// The smallest whole drop (voxels) steeper than tan(talus_angle) · distance.
int slidingDrop(double talus_angle, double distance) {
  const double slope = std::tan(talus_angle * std::numbers::pi / 180.0);
  return 1 + int(std::min(std::floor(slope * distance), 1e6));
}

// Whether the bits lo..hi (inclusive) of a column are all clear (air).
bool airFrom(const std::uint64_t* bits, int lo, int hi) {
  for (int word = lo / 64; word <= hi / 64; ++word) {
    const int first = std::max(lo, word * 64) - word * 64, last = std::min(hi, word * 64 + 63) - word * 64;
    const std::uint64_t mask = (~std::uint64_t(0) >> (63 - last)) & (~std::uint64_t(0) << first);
    if (bits[word] & mask) return false;
  }
  return true;
}

}  // namespace

ColluviumModel::ColluviumModel(const GridLayout& layout, const ColluviumParams& params, std::uint64_t seed)
    : layout_(layout),
      params_(params),
      seed_(seed),
      edge_drop_(slidingDrop(params.talus_angle, 1.0)),
      corner_drop_(slidingDrop(params.talus_angle, std::numbers::sqrt2)),
      yield_units_(std::llround(params.yield * double(kUnit))),
      accumulator_(std::size_t(layout.nx) * std::size_t(layout.ny), 0),
      tiles_x_((layout.nx + kSettleTile - 1) / kSettleTile) {}

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

int ColluviumModel::restingHeight(const std::uint64_t* bits, int z) const {
  std::size_t word = std::size_t(z) / 64;
  std::uint64_t below = bits[word] & ((std::uint64_t(1) << (z % 64)) - 1);
  while (below == 0 && word > 0) below = bits[--word];
  if (below != 0) return int(word * 64) + 63 - std::countl_zero(below) + 1;
  return layout_.ground ? 0 : -1;  // on the ground, or nothing to land on
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
  const int rest = restingHeight(bits, z);
  return rest < 0 ? -1 : std::int64_t(g.index(x, y, rest));
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
  // In blocks, in parallel; appended in block order.
  constexpr std::size_t kBlock = 2048;
  std::vector<std::vector<Cell>> found((emptied.size() + kBlock - 1) / kBlock);
  tbb::parallel_for(std::size_t(0), found.size(), [&](std::size_t b) {
    for (std::size_t k = b * kBlock; k < std::min(emptied.size(), (b + 1) * kBlock); ++k)
      forEachDisturbed(rock, emptied[k], [&](Cell d) { found[b].push_back(d); });
  });
  for (const std::vector<Cell>& f : found) unstable.insert(unstable.end(), f.begin(), f.end());
}

bool ColluviumModel::step(VoxelCoord& p, const VoxelCoord& lifted) const {
  const GridLayout& g = layout_;
  const auto solid = [](const std::uint64_t* bits, int z) { return (bits[z / 64] >> (z % 64)) & 1u; };
  const std::uint64_t* own = column(std::size_t(p.x) + std::size_t(g.nx) * std::size_t(p.y));
  if (p.z > 0 && !solid(own, p.z - 1)) {  // it falls
    const int rest = restingHeight(own, p.z - 1);
    if (rest < 0) return false;
    p.z = rest;
    return true;
  }
  // Covered: held in place (not by the cell it set out from, which it left).
  if (p.z + 1 < g.nz && solid(own, p.z + 1) && !(p.x == lifted.x && p.y == lifted.y && p.z + 1 == lifted.z))
    return false;
  // Top of a pile: slide to the neighbour column where it rests lowest, if
  // that drop is steeper than the talus angle allows: the column must be air
  // from the voxel's level down at least that drop.
  int best_x = 0, best_y = 0, best_rest = p.z;
  for (const auto& col : kColumns) {
    const int x = p.x + col[0], y = p.y + col[1];
    const int lowest = p.z - (col[0] != 0 && col[1] != 0 ? corner_drop_ : edge_drop_);
    if (lowest < 0) continue;
    if (x < 0 || y < 0 || x >= g.nx || y >= g.ny) {
      // Beyond the grid the ground goes on: a voxel that would slide off its edge leaves the grid
      // (the apron runs on past it) instead of piling against it.
      if (g.ground && best_rest > 0) best_rest = 0, best_x = x, best_y = y;
      continue;
    }
    const std::uint64_t* bits = column(std::size_t(x) + std::size_t(g.nx) * std::size_t(y));
    if (!airFrom(bits, lowest, p.z)) continue;
    const int rest = restingHeight(bits, lowest);
    if (rest >= 0 && rest < best_rest) {
      best_rest = rest;
      best_x = x, best_y = y;
    }
  }
  if (best_rest == p.z) return false;
  p = {best_x, best_y, best_rest};
  return true;
}

std::uint64_t ColluviumModel::settleTile(VoxelRock& rock, int tx, int ty, std::vector<Cell> cells,
                                         std::vector<Cell>& handed_on, std::vector<Cell>& moved, std::size_t& left) {
  const GridLayout& g = layout_;
  const std::size_t nx = std::size_t(g.nx), plane = nx * std::size_t(g.ny);
  // How many columns the column (x, y) lies outside the tile (Chebyshev).
  const int x0 = tx * kSettleTile, y0 = ty * kSettleTile;
  const auto outside = [&](int x, int y) {
    return std::max({x0 - x, x - (x0 + kSettleTile - 1), y0 - y, y - (y0 + kSettleTile - 1), 0});
  };
  const auto inside = [&](Cell c) {
    const std::size_t xy = c % plane;
    return outside(int(xy % nx), int(xy / nx)) == 0;
  };
  // A queue: each voxel is followed to rest before the next moves, and what
  // its leaving disturbed joins the back.
  std::uint64_t work = 0;
  for (std::size_t head = 0; head < cells.size(); ++head) {
    const Cell start = cells[head];
    if (rock.material[start] != Material::Colluvium) continue;
    const VoxelCoord from = g.coord(start);
    VoxelCoord p = from;
    bool stopped = false;  // at the edge of what this tile may touch, perhaps not at rest
    ++work;
    while (!stopped && step(p, from)) {
      ++work;
      if (!g.contains(p.x, p.y, 0)) break;
      stopped = outside(p.x, p.y) == kSettleReach;
    }
    if (!g.contains(p.x, p.y, 0)) {  // slid off the grid's edge
      setMaterial(rock, start, Material::Air);
      moved.push_back(start);
      ++left;
      forEachDisturbed(rock, start, [&](Cell d) { (inside(d) ? cells : handed_on).push_back(d); });
      continue;
    }
    const Cell at = Cell(g.index(p.x, p.y, p.z));
    if (at == start) continue;
    // The cells it passed through were held only for that moment: only its
    // start and its end change.
    setMaterial(rock, at, Material::Colluvium);
    setMaterial(rock, start, Material::Air);
    moved.push_back(start);
    moved.push_back(at);
    if (stopped) handed_on.push_back(at);  // the tile it reached takes it on
    forEachDisturbed(rock, start, [&](Cell d) { (inside(d) ? cells : handed_on).push_back(d); });
  }
  return work;
}

int ColluviumModel::tileOf(Cell c) const {
  const std::size_t nx = std::size_t(layout_.nx), xy = c % (nx * std::size_t(layout_.ny));
  return int(xy % nx) / kSettleTile + tiles_x_ * (int(xy / nx) / kSettleTile);
}

int ColluviumModel::colourOf(int tile) const {
  return (tile % tiles_x_) % 2 + 2 * ((tile / tiles_x_) % 2);
}

std::size_t ColluviumModel::settlePhase(VoxelRock& rock, std::vector<Cell>& cells, std::vector<Cell>& handed_on,
                                        std::vector<Cell>& moved) {
  // The phase's voxels by tile, then in cell order.
  std::vector<std::uint64_t> keyed(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) keyed[k] = std::uint64_t(tileOf(cells[k])) << 32 | cells[k];
  std::sort(keyed.begin(), keyed.end());
  keyed.erase(std::unique(keyed.begin(), keyed.end()), keyed.end());
  struct TileWork {
    int tile;
    std::vector<Cell> cells, handed_on, moved;
    std::uint64_t work = 0;
    std::size_t left = 0;
  };
  std::vector<TileWork> tiles;
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    const int tile = int(keyed[k] >> 32);
    if (tiles.empty() || tiles.back().tile != tile) tiles.push_back({tile, {}, {}, {}, 0, 0});
    tiles.back().cells.push_back(Cell(keyed[k]));
  }
  const auto run = [&](TileWork& t) {
    t.work = settleTile(rock, t.tile % tiles_x_, t.tile / tiles_x_, std::move(t.cells), t.handed_on, t.moved, t.left);
  };
  if (shuffle_seed_ == 0) {
    tbb::parallel_for(std::size_t(0), tiles.size(), [&](std::size_t k) { run(tiles[k]); });
  } else {
    std::vector<std::size_t> order(tiles.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    const auto key = [&](std::size_t k) { return counterHash(shuffle_seed_, purposeId("settle-tiles"), 0, k); };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
    for (std::size_t k : order) run(tiles[k]);
  }
  std::vector<std::uint64_t> work;
  std::size_t left = 0;
  for (const TileWork& t : tiles) {
    handed_on.insert(handed_on.end(), t.handed_on.begin(), t.handed_on.end());
    moved.insert(moved.end(), t.moved.begin(), t.moved.end());
    work.push_back(t.work);
    left += t.left;
  }
  noteWork(work);
  return left;
}

void ColluviumModel::noteWork(std::vector<std::uint64_t> tile_work) {
  std::sort(tile_work.begin(), tile_work.end(), std::greater<>());
  std::uint64_t workers[2] = {0, 0};
  for (std::uint64_t w : tile_work) {
    settle_work_.work += w;
    workers[workers[1] < workers[0] ? 1 : 0] += w;
  }
  if (tile_work.empty()) return;
  settle_work_.largest_tiles += tile_work.front();
  settle_work_.two_workers += std::max(workers[0], workers[1]);
}

std::size_t ColluviumModel::settle(VoxelRock& rock, std::vector<Cell>& unstable, std::vector<Cell>& changed,
                                   std::vector<Cell>& vacated) {
  track(rock);
  // What waits for each colour's phase; phases go round until none has any.
  std::array<std::vector<Cell>, 4> waiting;
  for (Cell c : unstable)
    if (rock.material[c] == Material::Colluvium) waiting[std::size_t(colourOf(tileOf(c)))].push_back(c);
  unstable.clear();
  std::vector<Cell> moved, handed_on;  // each move's start and end
  std::size_t left = 0;
  for (int idle = 0, colour = 0; idle < 4; colour = (colour + 1) % 4) {
    std::vector<Cell>& cells = waiting[std::size_t(colour)];
    if (cells.empty()) {
      ++idle;
      continue;
    }
    idle = 0;
    handed_on.clear();
    left += settlePhase(rock, cells, handed_on, moved);
    cells.clear();
    for (Cell c : handed_on) waiting[std::size_t(colourOf(tileOf(c)))].push_back(c);
  }
  // A cell is left when solid and entered when air, so its moves alternate:
  // an odd number of them changed it (an even number, nothing).
  tbb::parallel_sort(moved.begin(), moved.end());
  for (auto run = moved.begin(); run != moved.end();) {
    const Cell c = *run;
    const auto run_end = std::find_if(run, moved.end(), [c](Cell d) { return d != c; });
    if ((run_end - run) % 2 == 1) {
      changed.push_back(c);
      if (rock.material[c] == Material::Air) vacated.push_back(c);
    }
    run = run_end;
  }
  return left;
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
