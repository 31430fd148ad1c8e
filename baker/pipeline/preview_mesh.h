// The studio's preview of a rock (docs/studio.md, "The page"): the voxels' level-0
// surface smoothed as the preset's mesh.smoothing says, in the preview's narrow
// band (within half a voxel of the bake's surface, docs/meshes.md), with the
// bake's attributes sampled at its vertices and coloured in `palette`. No
// subdivision, detail, LODs or exports: what the page redraws after every cycle.
// Curvature costs a bubble count per exposed voxel, so exposure is computed only
// for the curvature palette, with `active` (the bubble graph and response in
// effect now: WeatheringSimulation::activeParams); the others read ½ (flat).
#pragma once

#include <cstdint>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

AssetMeshes previewMeshes(const VoxelRock& rock, const Preset& preset, const SimParams& active, Palette palette);

// At most about how much memory previewMeshes, or writing the rock's rock.vdb,
// takes on top of the rock: OpenVDB's level set and its working grids (goblin
// at resolution 128, 1.6 M cells: 27 MB for the mesh, 15 MB for the VDB, so
// 48 bytes a cell is generous), and 64 MiB for a malloc arena should one of the
// threads need a new one. OpenVDB cannot recover from running out part-way (it
// crashes), so the studio compares this with platform/memory.h's headroom first.
std::uint64_t estimatePreviewBytes(const GridLayout& layout);

}  // namespace rockbake
