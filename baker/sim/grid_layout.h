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

// Bytes the simulation needs for a layout, at most: materials (a byte a cell),
// integrity and durability over the whole domain (the margin holds no rock),
// the bit planes and work lists. The memory guard compares it with the
// machine's memory before allocating.
std::uint64_t estimateSimulationBytes(const GridLayout& layout);

// The same for a preset's parameters, with what the start adds: the signed
// distance fields of shape.variation and durability.rind, OpenVDB level sets
// over a band as wide as the variation's amplitude or the rind's depth on
// both sides of the boundary. About 80 bytes a band cell; the boundary is
// taken to be as large as the domain's outer faces, and the band at most the
// whole grid. Measured peaks at resolution 200: rounded-cobble (the band is
// the grid) 515 MiB against 530 estimated, goblin 157 against 435: on the
// safe side for slender rocks. This is the figure the memory guard and the
// out-of-memory message use.
std::uint64_t estimateSimulationBytes(const SimParams& params);

}  // namespace rockbake
