// Over-segmentation of one material's voxels into small near-convex parts
// (docs/collision.md, "Parts"): a regular grid of blocks, `block` voxels a
// side, cuts the voxels, and each block's voxels split into their 6-connected
// components. Parts are near-convex because they are small, and separate where the simulation
// separated the rock (a joint cut open, a fallen block).
// Coordinates are voxel index space: voxel (i, j, k) is the cube
// [i, i + 1] × [j, j + 1] × [k, k + 1] (docs/model.md §1).
// Deterministic whatever the thread count.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "collision/point_hull.h"
#include "core/voxel_rock.h"

namespace rockbake {

class AirCounter;  // collision/air_count.h

// The voxels of `material`: how many, and the box of cells that holds them
// (lo inclusive, hi exclusive; lo == hi when there are none).
struct VoxelBounds {
  std::size_t voxels = 0;
  std::array<int, 3> lo{}, hi{};
};
VoxelBounds materialBounds(const VoxelRock& rock, Material material);

struct VoxelPart {
  PointHull hull;          // of its voxel cubes
  std::size_t voxels = 0;  // how many voxels
  std::size_t air = 0;     // air voxels the hull holds (AirCounter)
};

struct VoxelParts {
  std::vector<VoxelPart> parts;  // blocks in z, y, x order; in a block, by first voxel in x-fastest order
  // Pairs of parts (a < b) with a voxel face between them, sorted, each once.
  std::vector<std::array<std::uint32_t, 2>> adjacent;
};

// `block`: 1..40 voxels a side; blocks start at `bounds.lo`. `air` counts
// the air of the same rock.
VoxelParts splitIntoParts(const VoxelRock& rock, Material material, const VoxelBounds& bounds, int block,
                          const AirCounter& air);

}  // namespace rockbake
