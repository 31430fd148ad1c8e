// The grid a preset simulates on (docs/model.md §1, §9): voxel size h from
// grid.resolution, an air margin as wide as the largest bubble reaches, and
// what the simulation needs in memory for it.
#pragma once

#include <cstdint>

#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

// h = longest side of grid.size / grid.resolution; margin = largest bubble
// reach + 1 voxels on the four sides and the top.
GridLayout computeGridLayout(const SimParams& params);

// Bytes the simulation needs for a layout, at most: materials (a byte a cell),
// integrity and durability over the whole domain (the margin holds no rock),
// the bit planes (colluvium's solid columns among them) and work lists. The
// memory guard compares it with the machine's memory before allocating.
std::uint64_t estimateSimulationBytes(const GridLayout& layout);

// The same for a preset's parameters, with what the start adds: the signed
// distance field of shape.variation and durability.rind (signedDistanceBytes:
// two bytes a cell, four when its reach is over 180 voxels). This is the
// figure the memory guard and the out-of-memory message use.
std::uint64_t estimateSimulationBytes(const SimParams& params);

}  // namespace rockbake
