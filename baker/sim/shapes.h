// The initial rock (docs/model.md §8): a resolved shape (inputs/resolve_shape.h)
// voxelized into the grid of computeGridLayout(params), integrity 1,
// durability from the graph.
#pragma once

#include <string>

#include "core/voxel_rock.h"
#include "inputs/resolve_shape.h"
#include "preset/preset.h"

namespace rockbake {

// A voxel is rock when its centre lies inside the shape. Rock is kept inside
// the domain (grid.size, or a family's fitted one); a shape reaching past it is
// clipped there, with a warning: logged, or put in `*warning` when given (so
// that the caller can say whose asset it is). The rock may be empty when the shape covers no voxel centre: the
// caller decides whether that is an error. Throws std::invalid_argument, before
// allocating, for a grid over kMaxSimulationCells (sim/grid_layout.h).
VoxelRock buildInitialRock(const ResolvedShape& shape, const SimParams& params, std::string* warning = nullptr);

// How far (world units) from the shape's boundary shape.variation reads its
// signed distance, on a grid of voxel size h: the amplitude and two voxels.
inline double variationReach(const ShapeVariation& variation, double h) {
  return variation.amplitude + 2 * h;
}

}  // namespace rockbake
