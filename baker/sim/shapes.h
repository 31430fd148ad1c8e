// The initial rock (SPEC §2.8): a primitive or an image voxelized into the
// grid of computeGridLayout(preset), integrity 1, durability from the graph.
#pragma once

#include "preset/preset.h"
#include "sim/voxel_rock.h"

namespace rockbake {

// A voxel is rock when its centre lies inside the shape. Rock is kept inside
// the preset's domain (grid.size); a shape reaching past it is clipped there.
// Throws InputError when the image cannot be read or the shape covers no voxel.
VoxelRock buildInitialRock(const Preset& preset);

}  // namespace rockbake
