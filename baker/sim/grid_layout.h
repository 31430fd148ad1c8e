// The grid a preset simulates on (docs/model.md §1, §9): voxel size h from
// grid.resolution, an air margin as wide as the largest bubble reaches, how
// many cells the simulation can number, and what it needs in memory.
#pragma once

#include <cstdint>
#include <limits>

#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

// h = longest side of grid.size / grid.resolution; margin = largest bubble
// reach + 1 voxels on the four sides and the top.
GridLayout computeGridLayout(const SimParams& params);

// The simulation numbers a grid's cells 0 … cellCount() − 1 in 32 bits (its
// work lists, rockfall's runs and colluvium's cells hold them by the million),
// so a grid has at most this many cells: 2³² − 1, about 1625³.
inline constexpr std::uint64_t kMaxSimulationCells = std::numeric_limits<std::uint32_t>::max();

// Throws std::invalid_argument, before anything is allocated, when `layout` has
// more than kMaxSimulationCells cells. The simulation's own guard: a preset
// whose grid is too large is refused earlier, at grid.resolution
// (pipeline/read_inputs.h).
void requireSimulationCells(const GridLayout& layout);

// The highest grid.resolution, at most params.grid.resolution, whose grid (its
// margin included) has at most kMaxSimulationCells cells; GridParams::kMinResolution
// when even that one has more. Computes layouts only.
int largestResolutionWithinCellLimit(const SimParams& params);

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
