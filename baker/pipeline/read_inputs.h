// What a bake checks and reads before it allocates the grid: the grid fits in
// this machine's memory (the simulation's own estimate), and the files the
// shape names read once (inputs/resolve_shape.h). `rockbake lint` runs the
// same checks, so a preset lint calls ok does not fail here.
#pragma once

#include "inputs/resolve_shape.h"
#include "preset/preset.h"

namespace rockbake {

// Throws InputError at grid.resolution when the grid would take more than 60 %
// of physical memory, or at the shape's keys when its files are unusable.
ResolvedShape readInputs(const Preset& preset);

// The memory check alone.
void checkGridFitsInMemory(const Preset& preset);

}  // namespace rockbake
