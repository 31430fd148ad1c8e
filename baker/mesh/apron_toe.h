// The debris apron's toe (docs/model.md §7, "The toe"). A pile of voxels ends at its rim in a
// step a voxel high, which smoothing rounds into a lip; a real talus apron runs out onto the
// ground along a long, gentle toe. The lowest `height` of every piece of colluvium resting on the
// ground is spread outwards, away from the rock: a vertex at height z < height near the apron's
// outer rim moves out by (height − z)(cot angle − cot kRimSlope), so that the band below `height`,
// about kRimSlope steep as the smoothed voxels leave it (goblin: 72°), comes to slope at `angle`; the ground cap under
// it follows, less and less inwards, so nothing folds. "Outwards" is along the gradient of the horizontal distance from
// the rock's own contact with the ground; "near the rim" is within the band's own width of the apron's outer rim
// (mesh/ground_contact.h). Heights do not change, so the apron keeps its height and its slope above the band; its
// footprint grows by the toe. Normals are recomputed.
#pragma once

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"

namespace rockbake {

// The slope the voxels leave the apron's rim at, for the toe's spread (degrees).
inline constexpr double kRimSlope = 70.0;

struct ApronToeParams {
  double angle = 12.0;   // degrees, (0, kRimSlope): the toe's slope
  double height = 1.25;  // voxels: how high the toe reaches
};

// `meshes` in the grid's world frame (before the pivot), both surfaces; changes the colluvium.
void shapeApronToe(AssetMeshes& meshes, const GridLayout& layout, const ApronToeParams& params);

}  // namespace rockbake
