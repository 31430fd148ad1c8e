// The studio's preview of a rock (docs/studio.md, "The page"): the voxels' level-0
// surface smoothed as the preset's mesh.smoothing says, in the preview's narrow
// band (within half a voxel of the bake's surface, docs/meshes.md), with the
// bake's attributes sampled at its vertices and coloured in `palette`. No
// subdivision, detail, LODs or exports: what the page redraws after every cycle.
// Curvature costs a bubble count per exposed voxel, so exposure is computed only
// for the curvature palette, with `active` (the bubble graph and response in
// effect now: WeatheringSimulation::activeParams); the others read ½ (flat).
#pragma once

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

AssetMeshes previewMeshes(const VoxelRock& rock, const Preset& preset, const SimParams& active, Palette palette);

}  // namespace rockbake
