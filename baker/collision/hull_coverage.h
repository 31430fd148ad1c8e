// How closely hulls fit one material's voxels (docs/collision.md, "Measures"):
// which voxel centres fall inside the union of the hulls (a centre on a hull's
// face counts as inside). For tests and benchmarks.
#pragma once

#include <cstddef>
#include <vector>

#include "collision/collision_hulls.h"
#include "core/voxel_rock.h"

namespace rockbake {

struct HullCoverage {
  std::size_t voxels = 0;         // voxels of the material
  std::size_t voxels_inside = 0;  // of them, those inside the union
  // Air voxels inside the union: all above the ground, where the grid starts.
  std::size_t air_inside = 0;
  double coverage() const { return voxels ? double(voxels_inside) / double(voxels) : 1.0; }
  // Air claimed per voxel of the material the hulls cover.
  double airPerVoxel() const { return voxels_inside ? double(air_inside) / double(voxels_inside) : 0.0; }
};

HullCoverage measureCoverage(const VoxelRock& rock, Material material, const std::vector<ConvexHull>& hulls);

}  // namespace rockbake
