#include "sim/rockfall.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/disjoint_set.h"

namespace rockbake {
namespace {

using Cell = std::uint32_t;

inline bool isSolid(Material m) {
  return m != Material::Air;
}

// The first x >= from in row[from, end) whose cell is not `solid` (solid or air), or end. Eight
// cells at a time while they are all alike: rows are long runs of air or of rock, and the rockfall
// check reads every cell of the grid each cycle.
int runEnd(const Material* row, int from, int end, bool solid) {
  static_assert(sizeof(Material) == 1 && std::uint8_t(Material::Air) == 0);
  constexpr std::uint64_t kOnes = 0x0101010101010101ull, kHighs = 0x8080808080808080ull;
  int x = from;
  for (; x + 8 <= end; x += 8) {
    std::uint64_t w;
    std::memcpy(&w, row + x, 8);
    const bool has_air = ((w - kOnes) & ~w & kHighs) != 0;  // some byte is zero
    if (solid ? has_air : w != 0) break;
  }
  while (x < end && isSolid(row[x]) == solid) ++x;
  return x;
}

// A 6-connected cluster of removed cells, and what its removal could have cut apart.
struct Cluster {
  VoxelCoord lo, hi;             // bounding box of the removed cells
  bool touches_ground = false;   // a removed cell was on the layer z = 0
  std::vector<Cell> neighbours;  // solid cells next to it, sorted
  // What a search must reach: every neighbour, and the ground if the cluster touched it.
  std::size_t goals() const { return neighbours.size() + (touches_ground ? 1 : 0); }
};

// The cluster of removed cells around `start`, the solid cells around it and its bounding box.
// Each cell gathered is marked in `clustered`; `cluster` is scratch. `Plane` is the solver's
// BitPlane (a template parameter because the type is private to it).
template <class Plane>
Cluster gatherCluster(const GridLayout& g, const VoxelRock& rock, Cell start, const Plane& removed, Plane& clustered,
                      std::vector<Cell>& cluster) {
  cluster.assign(1, start);
  clustered.set(start);
  Cluster k;
  k.lo = k.hi = g.coord(start);
  for (std::size_t i = 0; i < cluster.size(); ++i) {
    const VoxelCoord p = g.coord(cluster[i]);
    k.lo = {std::min(k.lo.x, p.x), std::min(k.lo.y, p.y), std::min(k.lo.z, p.z)};
    k.hi = {std::max(k.hi.x, p.x), std::max(k.hi.y, p.y), std::max(k.hi.z, p.z)};
    if (p.z == 0) k.touches_ground = true;
    for (const auto& o : kFaceNeighbours) {
      if (!g.contains(p.x + o[0], p.y + o[1], p.z + o[2])) continue;
      const Cell n = Cell(g.index(p.x + o[0], p.y + o[1], p.z + o[2]));
      if (isSolid(rock.material[n])) {
        k.neighbours.push_back(n);
      } else if (removed.test(n) && !clustered.test(n)) {
        clustered.set(n);
        cluster.push_back(n);
      }
    }
  }
  std::sort(k.neighbours.begin(), k.neighbours.end());
  k.neighbours.erase(std::unique(k.neighbours.begin(), k.neighbours.end()), k.neighbours.end());
  return k;
}

// The cells one cluster's searches visit, added to the count shared by all searches in
// batches; `failed` says some search has failed. Either ends every search early.
class VisitCount {
 public:
  VisitCount(std::atomic<std::size_t>& spent, const std::atomic<bool>& failed, std::size_t budget)
      : spent_(spent), failed_(failed), budget_(budget) {}
  // One more cell visited; false when the searches must stop.
  bool visit() { return ++unflushed_ != kFlush || (flush() && !failed_.load(std::memory_order_relaxed)); }
  // Adds the visits not yet counted to the shared count; false when it is over the budget.
  bool flush() {
    const std::size_t total = spent_.fetch_add(unflushed_, std::memory_order_relaxed) + unflushed_;
    unflushed_ = 0;
    return total <= budget_;
  }

 private:
  static constexpr std::size_t kFlush = 1024;
  std::atomic<std::size_t>& spent_;
  const std::atomic<bool>& failed_;
  std::size_t budget_;
  std::size_t unflushed_ = 0;
};

// Searches from one neighbour of `k` until every other neighbour is found, inside the
// cluster's box grown by `grow` voxels: paths found there are real paths, and the detours
// that matter are local. The ground joins every solid cell of the layer z = 0 (it holds them
// all up), so reaching that layer reaches the ground and, through it, the rest of the layer.
// `visited` (the solver's BitPlane) and `queue` are left clear.
template <class Plane>
bool connectedWithin(const GridLayout& g, const VoxelRock& rock, const Cluster& k, int grow, Plane& visited,
                     std::vector<Cell>& queue, VisitCount& count) {
  const std::size_t goals = k.goals();
  const VoxelCoord box_lo{k.lo.x - grow, k.lo.y - grow, k.lo.z - grow};
  const VoxelCoord box_hi{k.hi.x + grow, k.hi.y + grow, k.hi.z + grow};
  const auto inBox = [&](const VoxelCoord& q) {
    return g.contains(q.x, q.y, q.z) && q.x >= box_lo.x && q.y >= box_lo.y && q.z >= box_lo.z && q.x <= box_hi.x &&
           q.y <= box_hi.y && q.z <= box_hi.z;
  };
  std::size_t found = 0;
  bool ground_found = false;
  const auto visit = [&](Cell c) {
    if (visited.test(c) || !isSolid(rock.material[c])) return;
    visited.set(c);
    queue.push_back(c);
    if (std::binary_search(k.neighbours.begin(), k.neighbours.end(), c)) ++found;
  };
  // Every visited cell is in the queue: clearing it clears the plane.
  struct Unvisit {
    Plane& visited;
    std::vector<Cell>& queue;
    ~Unvisit() {
      for (Cell c : queue) visited.clear(c);
      queue.clear();
    }
  } unvisit{visited, queue};
  queue.clear();
  visit(k.neighbours.front());
  for (std::size_t head = 0; head < queue.size() && found < goals; ++head) {
    if (!count.visit()) return false;
    const VoxelCoord p = g.coord(queue[head]);
    if (p.z == 0 && !ground_found) {
      ground_found = true;
      if (k.touches_ground) ++found;
      for (int y = std::max(box_lo.y, 0); y <= std::min(box_hi.y, g.ny - 1); ++y)
        for (int x = std::max(box_lo.x, 0); x <= std::min(box_hi.x, g.nx - 1); ++x) visit(Cell(g.index(x, y, 0)));
    }
    for (const auto& o : kFaceNeighbours) {
      const VoxelCoord q{p.x + o[0], p.y + o[1], p.z + o[2]};
      if (inBox(q)) visit(Cell(g.index(q.x, q.y, q.z)));
    }
  }
  return found >= goals;
}

// A fallen voxel carries its history (its weathered skin falls with it); the cell it left keeps none.
void moveHistory(VoxelHistory& history, std::size_t from, std::size_t to) {
  for (RowSpans* spans : history.grids()) {
    spans->set(to, (*spans)[from]);
    spans->set(from, spans->fill);
  }
}

}  // namespace

RockfallSolver::RockfallSolver(const GridLayout& layout)
    : layout_(layout),
      removed_{std::vector<std::uint64_t>((layout.cellCount() + 63) / 64, 0)},
      clustered_{removed_.words},
      in_piece_{removed_.words},
      local_budget_(std::size_t(layout.ny) * std::size_t(layout.nz) * 4) {}

// For each 6-connected cluster K of removed cells, the solid cells next to K
// (and the ground, if K touched it) must still be connected to each other
// through solid. Then any path through K can be rerouted, so every cell keeps
// the ground connection it had. The searches stay near each cluster and within
// a budget; false means "not shown", and the caller labels the grid.
//
// The clusters are gathered first, then searched in parallel (each search
// reads the grid only). The answer does not depend on the order: it is false
// when some cluster's search fails or when the searches together visit more
// cells than the budget, whichever way they are scheduled.
bool RockfallSolver::removalKeepsSupport(const VoxelRock& rock, const std::vector<Cell>& removed) {
  const GridLayout& g = layout_;
  std::vector<Cluster> clusters;
  {
    // Mark the removed cells; those already put in a cluster are also clustered.
    for (Cell c : removed) removed_.set(c);
    struct Unmark {
      BitPlane &removed, &clustered;
      const std::vector<Cell>& cells;
      ~Unmark() {
        for (Cell c : cells) removed.clear(c), clustered.clear(c);
      }
    } unmark{removed_, clustered_, removed};
    std::vector<Cell> cluster;
    for (Cell start : removed) {
      if (clustered_.test(start)) continue;
      Cluster k = gatherCluster(g, rock, start, removed_, clustered_, cluster);
      // Nothing on one side of the cluster to be cut from the other: no search.
      if (k.goals() > 1) clusters.push_back(std::move(k));
    }
  }

  // Cells visited by all searches so far (flushed in batches), and whether
  // some search has failed: either ends every search early with "false".
  std::atomic<std::size_t> spent{0};
  std::atomic<bool> failed{false};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, clusters.size(), 1), [&](const auto& range) {
    Scratch& scratch = scratch_.local();
    if (scratch.visited.words.empty()) scratch.visited.words.assign((g.cellCount() + 63) / 64, 0);
    for (std::size_t index = range.begin(); index != range.end() && !failed.load(std::memory_order_relaxed); ++index) {
      const Cluster& k = clusters[index];
      VisitCount count(spent, failed, local_budget_);
      // Most clusters are settled within one voxel around them; a few need room.
      const bool shown = connectedWithin(g, rock, k, 1, scratch.visited, scratch.queue, count) ||
                         connectedWithin(g, rock, k, 4, scratch.visited, scratch.queue, count);
      if (!count.flush() || !shown) failed.store(true, std::memory_order_relaxed);
    }
  });
  return !failed.load() && spent.load() <= local_budget_;
}

// Solid cells not connected to the ground, in cell order. Labelling works on
// runs of solid cells along x: runs are found per layer in parallel, then
// runs that overlap in neighbouring rows are joined with union-find (a few
// runs per row, so this is cheap), and runs joined to a z = 0 run stand.
std::vector<Cell> RockfallSolver::floatingCells(const VoxelRock& rock) const {
  const GridLayout& g = layout_;
  struct Run {
    int x0, x1;  // inclusive
  };
  const std::size_t rows = std::size_t(g.ny) * std::size_t(g.nz);
  std::vector<std::vector<Run>> layer_runs(std::size_t(g.nz));
  std::vector<std::uint32_t> row_runs(rows, 0);  // runs per row
  tbb::parallel_for(0, g.nz, [&](int z) {
    auto& runs = layer_runs[std::size_t(z)];
    for (int y = 0; y < g.ny; ++y) {
      const Material* row = &rock.material[g.index(0, y, z)];
      std::uint32_t count = 0;
      for (int x = 0; x < g.nx;) {
        x = runEnd(row, x, g.nx, false);
        if (x == g.nx) break;
        const int x0 = x;
        x = runEnd(row, x, g.nx, true);
        runs.push_back({x0, x - 1});
        ++count;
      }
      row_runs[std::size_t(y) + std::size_t(g.ny) * std::size_t(z)] = count;
    }
  });
  std::vector<std::uint32_t> row_start(rows + 1, 0);
  for (std::size_t r = 0; r < rows; ++r) row_start[r + 1] = row_start[r] + row_runs[r];
  std::vector<Run> runs;
  runs.reserve(row_start[rows]);
  for (const auto& layer : layer_runs) runs.insert(runs.end(), layer.begin(), layer.end());

  DisjointSet components(runs.size());  // of runs
  // Joins the runs of two rows that overlap in x (face neighbours).
  const auto joinRows = [&](std::size_t a, std::size_t b) {
    std::uint32_t i = row_start[a], j = row_start[b];
    while (i < row_start[a + 1] && j < row_start[b + 1]) {
      if (runs[i].x1 >= runs[j].x0 && runs[j].x1 >= runs[i].x0) components.unite(i, j);
      if (runs[i].x1 < runs[j].x1)
        ++i;
      else
        ++j;
    }
  };
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y) {
      const std::size_t row = std::size_t(y) + std::size_t(g.ny) * std::size_t(z);
      if (y > 0) joinRows(row, row - 1);
      if (z > 0) joinRows(row, row - std::size_t(g.ny));
    }
  std::vector<std::uint8_t> grounded(runs.size(), 0);
  for (std::uint32_t i = 0; i < row_start[std::size_t(g.ny)]; ++i) grounded[components.find(i)] = 1;  // layer z = 0

  std::vector<Cell> floating;
  for (std::size_t row = 0; row < rows; ++row)
    for (std::uint32_t i = row_start[row]; i < row_start[row + 1]; ++i)
      if (!grounded[components.find(i)]) {
        const int y = int(row % std::size_t(g.ny)), z = int(row / std::size_t(g.ny));
        for (int x = runs[i].x0; x <= runs[i].x1; ++x) floating.push_back(Cell(g.index(x, y, z)));
      }
  return floating;
}

RockfallOutcome RockfallSolver::apply(VoxelRock& rock, RockfallMode mode, std::vector<Cell> removed_solid,
                                      bool label_everything) {
  RockfallOutcome outcome;
  if (mode == RockfallMode::Off || !layout_.ground) return outcome;
  // Cells refilled since they were vacated are solid again: not removed.
  std::erase_if(removed_solid, [&](Cell c) { return isSolid(rock.material[c]); });
  // Labelling costs about one visit per row of the grid; a removal that large
  // would cost the local test more than that, so it goes straight to labelling.
  const bool worth_a_local_test = removed_solid.size() < std::size_t(layout_.ny) * std::size_t(layout_.nz) / 2;
  if (!label_everything && worth_a_local_test && removalKeepsSupport(rock, removed_solid)) return outcome;
  outcome.labelled = true;
  const GridLayout& g = layout_;

  // Split the floating cells into 6-connected pieces (in cell order).
  const std::vector<Cell> floating = floatingCells(rock);
  if (floating.empty()) return outcome;
  std::vector<int> piece_of_floating(floating.size(), -1);
  const auto floatingIndex = [&](Cell c) -> std::ptrdiff_t {
    const auto it = std::lower_bound(floating.begin(), floating.end(), c);
    return (it != floating.end() && *it == c) ? it - floating.begin() : -1;
  };
  std::vector<std::vector<Cell>> pieces;
  for (std::size_t s = 0; s < floating.size(); ++s) {
    if (piece_of_floating[s] >= 0) continue;
    const int id = int(pieces.size());
    pieces.emplace_back(1, floating[s]);
    piece_of_floating[s] = id;
    auto& piece = pieces.back();
    for (std::size_t i = 0; i < piece.size(); ++i) {
      const VoxelCoord p = g.coord(piece[i]);
      for (const auto& o : kFaceNeighbours) {
        if (!g.contains(p.x + o[0], p.y + o[1], p.z + o[2])) continue;
        const std::ptrdiff_t f = floatingIndex(Cell(g.index(p.x + o[0], p.y + o[1], p.z + o[2])));
        if (f >= 0 && piece_of_floating[std::size_t(f)] < 0) {
          piece_of_floating[std::size_t(f)] = id;
          piece.push_back(floating[std::size_t(f)]);
        }
      }
    }
    std::sort(piece.begin(), piece.end());
  }

  // Drop the pieces, lowest first, in passes until none moves: a piece that
  // landed on another floating piece falls again once that one has moved.
  BitPlane& in_piece = in_piece_;
  const std::size_t layer = std::size_t(g.nx) * std::size_t(g.ny);
  for (bool moved = true; moved;) {
    moved = false;
    std::vector<std::size_t> order(pieces.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return pieces[a].front() < pieces[b].front(); });
    for (std::size_t id : order) {
      auto& piece = pieces[id];
      for (Cell c : piece) in_piece.set(c);
      // How far the piece can fall: the smallest air gap below any of its
      // cells that sits on something other than the piece itself.
      int drop = std::numeric_limits<int>::max();
      for (Cell c : piece) {
        const VoxelCoord p = g.coord(c);
        if (p.z > 0 && in_piece.test(Cell(c - layer))) continue;
        int gap = 0, z = p.z - 1;
        while (z >= 0 && !isSolid(rock.material[g.index(p.x, p.y, z)])) ++gap, --z;
        if (z >= 0 && in_piece.test(Cell(g.index(p.x, p.y, z)))) continue;
        drop = std::min(drop, gap);
      }
      for (Cell c : piece) in_piece.clear(c);
      if (drop == 0 || drop == std::numeric_limits<int>::max()) continue;
      moved = true;
      // Move bottom-up (cells are in ascending order, so z ascends).
      const std::size_t shift = std::size_t(drop) * layer;
      for (Cell c : piece) {
        const Cell to = Cell(c - shift);
        const bool crumble = mode == RockfallMode::Crumble && rock.material[c] == Material::Rock;
        outcome.crumbled += crumble ? 1 : 0;
        rock.material[to] = crumble ? Material::Colluvium : rock.material[c];
        rock.integrity.set(to, rock.integrity[c]);
        rock.durability.set(to, crumble ? 0.f : rock.durability[c]);
        if (!rock.rind.empty()) rock.rind[to] = crumble ? 0 : rock.rind[c];
        if (!rock.history.empty()) moveHistory(rock.history, c, to);
        rock.material[c] = Material::Air;
        rock.durability.set(c, 0.f);
        outcome.changed.push_back(c);
        outcome.changed.push_back(to);
      }
      outcome.fallen += piece.size();
      for (Cell& c : piece) c = Cell(c - shift);
    }
  }
  // A cell can be vacated by one move and landed on by another: report it once.
  std::sort(outcome.changed.begin(), outcome.changed.end());
  outcome.changed.erase(std::unique(outcome.changed.begin(), outcome.changed.end()), outcome.changed.end());
  return outcome;
}

}  // namespace rockbake
