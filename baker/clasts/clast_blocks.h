// The blocks stones start from (docs/model.md §13): a talus stone is a piece of the rock's own
// jointed mass, bounded by joint and bedding faces, before weathering rounds it. Each block is a
// box of seeded proportions (Zingg's classes: blades, discs, rods and cubes) with a few corners
// knocked off by seeded oblique cuts. Its shortest axis is z, so it rests on its broadest face.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "core/voxel_rock.h"

namespace rockbake {

struct ClastBlock {
  Vec3d half_extents{0.5, 0.5, 0.5};  // x >= y >= z, world units; x is half the longest axis
  // Oblique cuts: the block keeps the points p (about its centre) with dot(normal, p) <= offset.
  struct Cut {
    Vec3d normal;  // unit
    double offset;
  };
  std::vector<Cut> cuts;
};

// Block `index` of `seed`'s stones, its longest axis `length` world units. Pure function.
ClastBlock drawClastBlock(std::uint64_t seed, int index, double length);

// Marks as rock every cell of `layout` whose centre lies in `block`, centred in the grid (air
// elsewhere), with integrity 1 and durability `durability`.
VoxelRock voxelizeClastBlock(const ClastBlock& block, const GridLayout& layout, float durability);

}  // namespace rockbake
