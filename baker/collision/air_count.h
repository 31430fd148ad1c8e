// Air voxels inside a convex polytope, counted without visiting them
// (docs/collision.md, "Merging"): each x-row of the grid keeps running counts
// of its air cells, so a row's air between two x bounds is one subtraction,
// and a polytope's air is one interval per row it crosses. Voxel index space
// (voxel (i, j, k) is centred on (i + ½, j + ½, k + ½)); a centre on the
// polytope's boundary counts as inside, as in hull_coverage.h. Memory: two
// bytes per cell of the box it covers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "collision/point_hull.h"
#include "collision/voxel_parts.h"
#include "core/voxel_rock.h"

namespace rockbake {

class AirCounter {
 public:
  // Counts Material::Air cells within `box` (a material's VoxelBounds).
  AirCounter(const VoxelRock& rock, const VoxelBounds& box);
  // Air cells whose centres lie in ∩ {normal · x <= offset} and in the box [lo, hi] (index space).
  std::size_t count(const std::vector<HullPlane>& planes, const Vec3d& lo, const Vec3d& hi) const;

 private:
  std::array<int, 3> lo_{}, size_{};
  std::vector<std::uint16_t> prefix_;  // per row (y, z) of the box: size_[0] + 1 running counts
};

}  // namespace rockbake
