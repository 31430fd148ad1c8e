// How alike two weathered rocks are, and their proportions (docs/model.md §12):
// the measures a family's variety is judged by, on the rock voxels alone.
#pragma once

#include <array>

#include "core/voxel_rock.h"

namespace rockbake {

// The aligned IoU of two rocks: `b` scaled to `a`'s rock volume, both stood on
// their footprint centroid (the mean x, y of their rock voxels) and their
// lowest rock voxel, `b` turned about the vertical in 10° steps, and mirrored;
// the best intersection over union of those 72 poses. 1 for a rock against
// itself turned or mirrored; about 0.15–0.4 for two unrelated rocks. The
// voxels of `b` are resampled on `a`'s lattice (nearest voxel). 0 when either
// has no rock.
double alignedIoU(const VoxelRock& a, const VoxelRock& b);

// The rock voxels' principal axes: the square roots of their covariance's
// eigenvalues (world units), largest first (a ≥ b ≥ c; Zingg's b/a and c/b
// are their ratios). Zeros when there is no rock.
std::array<double, 3> principalAxes(const VoxelRock& rock);

}  // namespace rockbake
