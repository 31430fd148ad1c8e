// The grid a preset simulates on (SPEC §2.1, §2.9): voxel size h from
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

// Bytes the simulation needs for a layout (grids, bit planes, work lists): the
// memory guard compares it with the machine's memory before allocating.
std::uint64_t estimateSimulationBytes(const GridLayout& layout);

}  // namespace rockbake
