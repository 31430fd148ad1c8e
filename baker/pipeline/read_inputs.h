// What a bake checks and reads before it allocates the grid: the simulation
// can number the grid's cells, the grid fits in this machine's memory (the
// simulation's own estimate), and the files the shape names read once
// (inputs/resolve_shape.h). `rockbake lint` runs the same checks, so a preset
// lint calls ok does not fail here.
#pragma once

#include <string>

#include "inputs/resolve_shape.h"
#include "preset/preset.h"

namespace rockbake {

// Throws InputError at grid.resolution when the grid has more cells than the
// simulation numbers or would take more than 60 % of physical memory, or at the
// shape's keys when its files are unusable.
ResolvedShape readInputs(const Preset& preset);

// The cell check alone: InputError at grid.resolution when the grid, margin
// included, has more than kMaxSimulationCells cells (sim/grid_layout.h), naming the
// highest resolution that fits. The same on every machine, so it comes first.
void checkGridCellCount(const Preset& preset);

// The memory check alone.
void checkGridFitsInMemory(const Preset& preset);

// What to say when memory runs out while `preset` bakes all the same (the
// estimate is the simulation's; meshing and libraries take more):
// "out of memory: lower grid.resolution (N needs about X MiB for the
// simulation alone)".
std::string outOfMemoryMessage(const Preset& preset);

}  // namespace rockbake
