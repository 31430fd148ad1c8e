// The debris apron's toe (docs/model.md §7, "The toe"). A pile of voxels ends at its rim in a
// step a voxel high, which smoothing rounds into a lip; a real talus apron runs out onto the
// ground along a long, gentle toe. The lowest `height` of every piece of colluvium resting on the
// ground is spread outwards, away from the rock: with s = height (cot angle − cot kRimSlope) (the
// band is about kRimSlope steep as the smoothed voxels leave it: 72° on goblin), a vertex at
// height z and horizontal distance e inside the apron's outer rim (mesh/ground_contact.h) moves
// out by max(0, s (1 − z / height) − e / 2). The rim moves out by s, the band the less the higher
// it lies, so it comes to slope at about `angle`; further in, the shift falls by half of what a
// vertex lies further in, so nothing overtakes what lies beyond it and nothing folds. "Outwards"
// is along the gradient of the horizontal distance from the rock's own contact with the ground.
// Heights do not change: the apron keeps its height and its slope above the band; its footprint
// grows by the toe. Normals are recomputed.
#pragma once

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"

namespace rockbake {

// The slope the voxels leave the apron's rim at, for the toe's spread (degrees).
inline constexpr double kRimSlope = 70.0;

struct ApronToeParams {
  double angle = 12.0;  // degrees, (0, kRimSlope): the toe's slope
  double height = 1.5;  // voxels: how high the toe reaches
};

// `meshes` in the grid's world frame (before the pivot), both surfaces; changes the colluvium.
void shapeApronToe(AssetMeshes& meshes, const GridLayout& layout, const ApronToeParams& params);

}  // namespace rockbake
