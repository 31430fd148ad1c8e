#include "collision/voxel_parts.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "collision/air_count.h"

namespace rockbake {
namespace {

constexpr int kMaxBlock = 40;  // a bound for sanity: larger blocks only make parts less convex
constexpr std::uint32_t kUnlabelled = std::numeric_limits<std::uint32_t>::max();

// One block of the grid of blocks: its cells and, once split, a label per
// cell (0: another material; 1, 2, …: its parts, parts[label - 1]).
struct Block {
  std::array<int, 3> lo{}, size{};
  std::vector<std::uint32_t> labels;  // empty when the block holds none of the material
  std::vector<VoxelPart> parts;

  std::size_t local(int x, int y, int z) const {
    return std::size_t(x) + std::size_t(size[0]) * (std::size_t(y) + std::size_t(size[1]) * std::size_t(z));
  }
  template <typename Visit>
  void forEachCell(Visit visit) const {
    for (int z = 0; z < size[2]; ++z)
      for (int y = 0; y < size[1]; ++y)
        for (int x = 0; x < size[0]; ++x) visit(x, y, z);
  }
};

// Labels the block's 6-connected components in scan order (x fastest);
// returns how many there are.
std::uint32_t labelComponents(const VoxelRock& rock, Material material, Block& b) {
  const GridLayout& g = rock.layout;
  b.labels.assign(std::size_t(b.size[0]) * std::size_t(b.size[1]) * std::size_t(b.size[2]), 0);
  bool any = false;
  b.forEachCell([&](int x, int y, int z) {
    if (rock.material[g.index(b.lo[0] + x, b.lo[1] + y, b.lo[2] + z)] == material)
      b.labels[b.local(x, y, z)] = kUnlabelled, any = true;
  });
  if (!any) {
    b.labels.clear();
    return 0;
  }
  std::uint32_t count = 0;
  std::vector<std::array<int, 3>> stack;
  b.forEachCell([&](int x, int y, int z) {
    if (b.labels[b.local(x, y, z)] != kUnlabelled) return;
    const std::uint32_t label = ++count;
    b.labels[b.local(x, y, z)] = label;
    stack.push_back({x, y, z});
    while (!stack.empty()) {
      const std::array<int, 3> c = stack.back();
      stack.pop_back();
      for (const auto& d : kFaceNeighbours) {
        const std::array<int, 3> n{c[0] + d[0], c[1] + d[1], c[2] + d[2]};
        if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= b.size[0] || n[1] >= b.size[1] || n[2] >= b.size[2]) continue;
        std::uint32_t& l = b.labels[b.local(n[0], n[1], n[2])];
        if (l == kUnlabelled) l = label, stack.push_back(n);
      }
    }
  });
  return count;
}

// Each part's voxel count and hull (of the eight corners of each x-run's two
// end faces: the hull of its voxel cubes), and the air the hull holds.
void gatherParts(Block& b, std::uint32_t count, const AirCounter& air) {
  std::vector<std::vector<Vec3d>> corners(count);
  b.parts.resize(count);
  for (int z = 0; z < b.size[2]; ++z)
    for (int y = 0; y < b.size[1]; ++y)
      for (int x = 0; x < b.size[0];) {
        const std::uint32_t label = b.labels[b.local(x, y, z)];
        int end = x + 1;
        while (end < b.size[0] && b.labels[b.local(end, y, z)] == label) ++end;
        if (label != 0) {
          b.parts[label - 1].voxels += std::size_t(end - x);
          const double gy = b.lo[1] + y, gz = b.lo[2] + z;
          for (const double gx : {double(b.lo[0] + x), double(b.lo[0] + end)})
            for (const double cy : {gy, gy + 1})
              for (const double cz : {gz, gz + 1}) corners[label - 1].push_back({gx, cy, cz});
        }
        x = end;
      }
  for (std::uint32_t i = 0; i < count; ++i) {
    std::vector<Vec3d>& c = corners[i];
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    VoxelPart& part = b.parts[i];
    part.hull = hullOfPoints(c);
    Vec3d lo = part.hull.vertices.front(), hi = lo;
    for (const Vec3d& v : part.hull.vertices)
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
    part.air = air.count(part.hull.planes, lo, hi);
  }
}

}  // namespace

VoxelBounds materialBounds(const VoxelRock& rock, Material material) {
  const GridLayout& g = rock.layout;
  VoxelBounds bounds;
  bounds.lo = {g.nx, g.ny, g.nz};
  bounds.hi = {0, 0, 0};
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y) {
      const Material* row = &rock.material[g.index(0, y, z)];
      for (int x = 0; x < g.nx; ++x) {
        if (row[x] != material) continue;
        ++bounds.voxels;
        const int c[3] = {x, y, z};
        for (int a = 0; a < 3; ++a)
          bounds.lo[a] = std::min(bounds.lo[a], c[a]), bounds.hi[a] = std::max(bounds.hi[a], c[a] + 1);
      }
    }
  if (bounds.voxels == 0) bounds.lo = bounds.hi = {0, 0, 0};
  return bounds;
}

VoxelParts splitIntoParts(const VoxelRock& rock, Material material, const VoxelBounds& bounds, int block,
                          const AirCounter& air) {
  if (block < 1 || block > kMaxBlock)
    throw std::invalid_argument("splitIntoParts: block " + std::to_string(block) + " outside 1.." +
                                std::to_string(kMaxBlock));
  std::array<int, 3> count{};
  for (int a = 0; a < 3; ++a) count[a] = (bounds.hi[a] - bounds.lo[a] + block - 1) / block;
  std::vector<Block> blocks(std::size_t(count[0]) * std::size_t(count[1]) * std::size_t(count[2]));
  const auto blockIndex = [&](const std::array<int, 3>& ijk) {
    return std::size_t(ijk[0]) +
           std::size_t(count[0]) * (std::size_t(ijk[1]) + std::size_t(count[1]) * std::size_t(ijk[2]));
  };
  tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t n) {
    Block& b = blocks[n];
    const std::size_t ij = std::size_t(count[0]) * std::size_t(count[1]);
    const int ijk[3] = {int(n % std::size_t(count[0])), int((n % ij) / std::size_t(count[0])), int(n / ij)};
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = bounds.lo[a] + ijk[a] * block;
      b.size[a] = std::min(block, bounds.hi[a] - b.lo[a]);
    }
    if (const std::uint32_t count = labelComponents(rock, material, b)) gatherParts(b, count, air);
  });

  // Global part numbers: blocks in order, each block's parts in order.
  std::vector<std::uint32_t> first(blocks.size() + 1, 0);
  for (std::size_t n = 0; n < blocks.size(); ++n) first[n + 1] = first[n] + std::uint32_t(blocks[n].parts.size());

  // Faces between a cell and its +x, +y, +z neighbours that hold different parts.
  std::vector<std::vector<std::array<std::uint32_t, 2>>> pairs(blocks.size());
  tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t n) {
    const Block& b = blocks[n];
    if (b.labels.empty()) return;
    const std::size_t ij = std::size_t(count[0]) * std::size_t(count[1]);
    const std::array<int, 3> ijk{int(n % std::size_t(count[0])), int((n % ij) / std::size_t(count[0])), int(n / ij)};
    auto& out = pairs[n];
    b.forEachCell([&](int x, int y, int z) {
      const std::uint32_t here = b.labels[b.local(x, y, z)];
      if (here == 0) return;
      for (int axis = 0; axis < 3; ++axis) {
        std::array<int, 3> c{x, y, z};
        ++c[axis];
        std::size_t m = n;
        if (c[axis] == b.size[axis]) {  // in the next block
          std::array<int, 3> next = ijk;
          if (++next[axis] >= count[axis]) continue;
          m = blockIndex(next);
          c[axis] = 0;
        }
        const Block& other = blocks[m];
        if (other.labels.empty()) continue;
        const std::uint32_t there = other.labels[other.local(c[0], c[1], c[2])];
        if (there == 0 || (m == n && there == here)) continue;
        const std::uint32_t p = first[n] + here - 1, q = first[m] + there - 1;
        out.push_back({std::min(p, q), std::max(p, q)});
      }
    });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  });

  VoxelParts result;
  result.parts.reserve(first.back());
  for (Block& b : blocks)
    for (VoxelPart& p : b.parts) result.parts.push_back(std::move(p));
  for (const auto& out : pairs) result.adjacent.insert(result.adjacent.end(), out.begin(), out.end());
  std::sort(result.adjacent.begin(), result.adjacent.end());
  result.adjacent.erase(std::unique(result.adjacent.begin(), result.adjacent.end()), result.adjacent.end());
  return result;
}

}  // namespace rockbake
