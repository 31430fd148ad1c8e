// How many Catmull-Clark levels the mesh stage spends (docs/meshes.md, Subdivision
// serves coarse grids). `mesh.subdivision` is the most it may spend; a level
// is spent only while it is needed: while the refined edges, about one voxel
// long after extraction and halved by each level, are longer than a quarter
// of the detail's period (four vertices to each grain of `mesh.detail`).
// Without detail (absent, or amplitude 0) nothing is measured in world units,
// and every level the preset asks for is spent.
//
// What a level adds below the voxel is room for the detail: LOD0 keeps as
// close to the extraction as to a subdivided surface. At the house resolution
// (every shipped preset at its own resolution) the voxels are coarser than
// that and the preset's level is spent as before; at a hero resolution (goblin
// at 384: voxels of 0.016 against grains of 0.08) none is, and LOD0 is
// simplified from the extraction directly: a quarter of the triangles to make
// and to take out again.
#pragma once

#include <optional>

#include "preset/preset.h"

namespace rockbake {

// Levels in 0..max_levels for voxels `voxel` world units wide (> 0).
int refinementLevels(int max_levels, double voxel, const std::optional<NoiseParams>& detail);

}  // namespace rockbake
