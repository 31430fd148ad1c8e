// The voxel rock: a dense grid of materials with per-voxel integrity and
// durability (docs/model.md §1). Plain data the simulation gives to the mesh, export
// and render stages. Materials take a byte per cell; integrity and durability
// are kept only on each x-row's span of cells that ever held rock (RowSpans),
// so a grid that is mostly air costs about one byte per cell plus eight per
// rock voxel.
//
// Layout: x fastest, then y, then z (z up). Voxel (i, j, k) spans
//   [origin + (i, j, k) h, origin + (i + 1, j + 1, k + 1) h]
// in world units. The grid covers the preset's domain (grid.size) plus an air
// margin of `margin` voxels on the four sides and the top, wide enough for the
// largest bubble; k = 0 sits on the ground (world z = 0).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace rockbake {

enum class Material : std::uint8_t { Air = 0, Rock = 1, Colluvium = 2 };

struct VoxelCoord {
  int x, y, z;
};

// The six face-neighbour offsets.
inline constexpr int kFaceNeighbours[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

struct GridLayout {
  int nx = 0, ny = 0, nz = 0;  // voxels, margin included
  int margin = 0;              // air voxels added beside and above the domain
  double h = 1.0;              // voxel edge, world units
  Vec3d origin{};              // world position of voxel (0, 0, 0)'s min corner
  double domain_height = 1.0;  // grid.size z: altitude 1 (world units)
  bool ground = true;          // a solid, never-weathering layer below k = 0

  std::size_t cellCount() const { return std::size_t(nx) * std::size_t(ny) * std::size_t(nz); }
  std::size_t index(int x, int y, int z) const {
    return std::size_t(x) + std::size_t(nx) * (std::size_t(y) + std::size_t(ny) * std::size_t(z));
  }
  VoxelCoord coord(std::size_t index) const {
    const std::size_t layer = std::size_t(nx) * std::size_t(ny);
    return {int(index % std::size_t(nx)), int((index % layer) / std::size_t(nx)), int(index / layer)};
  }
  bool contains(int x, int y, int z) const { return x >= 0 && y >= 0 && z >= 0 && x < nx && y < ny && z < nz; }
  // World coordinates of a voxel centre.
  Vec3d center(int x, int y, int z) const {
    return {origin[0] + (x + 0.5) * h, origin[1] + (y + 0.5) * h, origin[2] + (z + 0.5) * h};
  }
  // Normalised altitude of layer z's centre: 0 at the ground, 1 at the top of grid.size.
  double altitude(int z) const { return (origin[2] + (z + 0.5) * h) / domain_height; }
};

// One float per cell, stored only from the first to the last cell set in each
// x-row (y, z); every other cell reads `fill`. Reads and writes equal those of
// a dense array filled with `fill`. Writes to different rows may run in
// parallel; a write outside its row's span grows that row (setting `fill`
// there never does).
struct RowSpans {
  float fill = 0.f;
  int nx = 0;                              // cells per row
  std::vector<std::int32_t> first;         // per row (y + ny z): x of values[row][0]
  std::vector<std::vector<float>> values;  // per row

  RowSpans() = default;
  RowSpans(const GridLayout& layout, float fill_value)
      : fill(fill_value),
        nx(layout.nx),
        first(std::size_t(layout.ny) * std::size_t(layout.nz), 0),
        values(first.size()) {}

  float at(std::size_t row, int x) const {
    const std::vector<float>& v = values[row];
    const std::size_t i = std::size_t(std::int64_t(x) - first[row]);  // huge when x < first
    return i < v.size() ? v[i] : fill;
  }
  float operator[](std::size_t cell) const { return at(cell / std::size_t(nx), int(cell % std::size_t(nx))); }
  void set(std::size_t row, int x, float value);
  void set(std::size_t cell, float value) { set(cell / std::size_t(nx), int(cell % std::size_t(nx)), value); }
  bool covers(std::size_t row, int x) const { return std::size_t(std::int64_t(x) - first[row]) < values[row].size(); }
  // Grows row's span to hold [x_lo, x_hi] exactly (new cells read fill), so
  // that later writes there need no allocation.
  void cover(std::size_t row, int x_lo, int x_hi);
  // The stored value of a covered cell, for writes from parallel tasks.
  float& slot(std::size_t row, int x) { return values[row][std::size_t(std::int64_t(x) - first[row])]; }
  // Cells held in the spans (for memory figures and tests).
  std::size_t storedCells() const;
  // Every cell's value, as one dense array of nx × rows (for tests).
  std::vector<float> toDense() const;
};

// What each rock voxel's surface went through (docs/model.md §14), in cycles: 0 is the blockout
// before the first cycle, k the k-th cycle (1-based), −1 never. Kept like integrity, on each row's
// span of the cells ever set, and moved with the rock that falls.
struct VoxelHistory {
  RowSpans exposed;      // the cycle a face of the voxel first opened to air
  RowSpans covered;      // the last cycle it had a face on colluvium
  RowSpans covered_for;  // how many cycles it had a face on colluvium (fill 0)
  RowSpans scarred;      // the last cycle rockfall opened its surface (docs/model.md §14)
  int cycles = 0;        // the cycles recorded: the last one's number

  VoxelHistory() = default;
  explicit VoxelHistory(const GridLayout& layout)
      : exposed(layout, -1.f), covered(layout, -1.f), covered_for(layout, 0.f), scarred(layout, -1.f) {}
  bool empty() const { return exposed.first.empty(); }
  // The four grids in one order, for what treats them alike (moving, checking, storing them).
  std::array<RowSpans*, 4> grids() { return {&exposed, &covered, &covered_for, &scarred}; }
  std::array<const RowSpans*, 4> grids() const { return {&exposed, &covered, &covered_for, &scarred}; }
};

struct VoxelRock {
  GridLayout layout;
  std::vector<Material> material;  // cellCount()
  RowSpans integrity;              // 1 at the start, rock voxels only meaningful
  RowSpans durability;             // > 0 on rock voxels, 0 elsewhere
  // Empty without a rind (durability.rind); else cellCount(): the part
  // (0..255) of each voxel within the rind's depth of the initial surface.
  // Falls with its rock; keyframes re-read it.
  std::vector<std::uint8_t> rind;
  // Empty until the simulation starts (it records every cycle from then on).
  VoxelHistory history;

  std::size_t count(Material m) const;
};

// How much two rocks on the same layout overlap: rock voxels in both over rock
// voxels in either (1 when neither has rock); std::invalid_argument for two
// layouts. Seeds of a family lie on grids of their own: sim/rock_measures.h
// compares those.
double rockIntersectionOverUnion(const VoxelRock& a, const VoxelRock& b);

// Sets integrity to 1 and durability to 0 everywhere, with both spans sized
// to each row's rock cells (so assigning them allocates nothing more).
void resetRockValues(VoxelRock& rock);

}  // namespace rockbake
