// A family's individual (docs/model.md §12): what one seed draws from a
// preset's `family:` ranges, and the grid fitted to it.
//
// The blockout is the shape as the preset gives it, in the preset's own
// grid.size (its base centre at the centre of the domain's footprint, on the
// ground). The individual is that blockout scaled, stretched along its own
// axes, tapered, twisted and bent along its height, tilted, turned about the
// vertical and cut along the joint sets' planes; the grid it weathers in is
// fitted to it, with room on every side for the debris apron. The voxel size
// stays the preset's (longest side of grid.size / grid.resolution), so a
// larger individual has more voxels, not coarser ones.
//
// Without `family:` the individual is the blockout itself in grid.size,
// exactly as before families existed. Every draw is a pure function of
// (seed, purpose, index): the same preset and seed give the same individual.
#pragma once

#include <vector>

#include "core/vec3.h"
#include "preset/preset.h"

namespace rockbake {

struct Individual {
  bool drawn = false;  // false: no family, the blockout as given
  double scale = 1.0;
  Vec3d stretch{1.0, 1.0, 1.0};  // along the blockout's own x, y, z
  double azimuth = 0.0;          // degrees about +z, counter-clockwise seen from above
  double tilt = 0.0;             // degrees
  double tilt_toward = 0.0;      // degrees: the direction the top leans to, from +x counter-clockwise
  double bend = 0.0;             // the top's sideways offset, a fraction of the height
  double bend_toward = 0.0;      // degrees, from +x counter-clockwise (before the azimuth)
  double taper = 0.0;            // width at the top / width at the base − 1, as a signed fraction
  double twist = 0.0;            // degrees the top turns relative to the base
  struct Cut {
    std::size_t joint_set = 0;  // durability.joints[joint_set] gives the plane's orientation
    Vec3d normal{0, 0, 1};      // unit, in the fitted grid's world frame: the side cut away
    double depth = 0.0;         // fraction of the shape's width along `normal` cut away
  };
  std::vector<Cut> cuts;
  Vec3d domain{};       // the fitted grid.size, world units
  Vec3d pivot{};        // where the blockout's base centre stands in the fitted domain
  double apron = 0.0;   // room left for the debris apron beyond the rock's footprint, world units
  double height = 0.0;  // the scaled blockout's height: the bend and taper are along it
  // Where the transformed blockout box lies in the fitted domain (world units), a margin
  // included: no rock outside it, so the start need not look there. Only when drawn.
  Vec3d box_lo{}, box_hi{};
};

// Where the blockout's base centre stands in its own frame (grid.size): shape.center, or the
// footprint's centre on the ground.
Vec3d blockoutBaseCenter(const SimParams& params);

// The individual `params.seed` draws from `params.family`; without a family,
// the blockout in grid.size (domain = grid.size, centred, nothing changed).
Individual drawIndividual(const SimParams& params);

// The grid size a preset simulates in: the individual's fitted domain.
Vec3d simulationDomain(const SimParams& params);

// The durability parameters the individual's geology is read with: strata and
// joint strikes turned by its azimuth when `family.geology` is `turns`.
DurabilityParams individualDurability(const SimParams& params);

// Maps a point of the fitted domain (world units) back into the blockout's
// frame: the preset's grid.size, where the shape's inside test is defined.
// Exact inverse of the individual's warp, tilt and turn.
Vec3d toBlockout(const Individual& individual, const SimParams& params, const Vec3d& world);

}  // namespace rockbake
