// The voxel rock: a dense grid of materials with per-voxel integrity and
// durability (SPEC §2.1). Plain data the simulation gives to the mesh, export
// and render stages.
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

struct VoxelRock {
  GridLayout layout;
  std::vector<Material> material;  // cellCount()
  std::vector<float> integrity;    // cellCount(); 1 at the start, rock voxels only meaningful
  std::vector<float> durability;   // cellCount(); > 0 on rock voxels, 0 elsewhere
  // Empty without a rind (durability.rind); else cellCount(): the part
  // (0..255) of each voxel within the rind's depth of the initial surface.
  // Falls with its rock; keyframes re-read it.
  std::vector<std::uint8_t> rind;

  std::size_t count(Material m) const;
};

}  // namespace rockbake
