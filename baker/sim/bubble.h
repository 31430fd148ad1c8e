// Bubbles: the neighbourhoods whose air fraction estimates curvature (docs/model.md §3).
//
// A Bubble is a finite, symmetric set of integer voxel offsets that contains 0,
// stored both as a list and as x-intervals ("rows") for fast counting.
// Estimators flatten `collection`s into weighted members; the calibrated
// exposure s of an estimator is the weighted mean of its members' s.
#pragma once

#include <array>
#include <vector>

#include "preset/preset.h"

namespace rockbake {

struct Bubble {
  using Offset = std::array<int, 3>;
  // One run of offsets along x: {(x, dy, dz) : x_min <= x <= x_max}.
  struct Row {
    int dy, dz, x_min, x_max;
  };

  std::vector<Offset> offsets;  // sorted by (dz, dy, dx)
  std::vector<Row> rows;        // the same offsets as x-intervals
  int reach = 0;                // largest |component| of any offset, voxels
  double alpha_flat = 0.5;      // α on a flat face, averaged over the six orientations
};

// Offsets are chosen in voxel units: `extents` are the sphere radius (in [0]),
// ellipsoid radii or box half extents, already divided by the voxel size.
Bubble makeSphereBubble(double radius_voxels);
Bubble makeEllipsoidBubble(const Vec3d& radii_voxels);
Bubble makeBoxBubble(const Vec3d& half_extents_voxels);
Bubble makeBubbleFromOffsets(std::vector<Bubble::Offset> offsets);  // must be symmetric with 0

// α on a flat face whose outward normal is `axis` (0..5 = +x, -x, +y, -y, +z, -z).
double flatFaceAlpha(const Bubble& bubble, int axis);

// s from α (docs/model.md §3): ½ on a flat face, towards 1 when convex, towards 0 when concave.
inline double calibratedExposure(double alpha, double alpha_flat) {
  if (alpha <= alpha_flat) return 0.5 * alpha / alpha_flat;
  return 0.5 + 0.5 * (alpha - alpha_flat) / (1.0 - alpha_flat);
}

struct BubbleEstimator {
  struct Member {
    Bubble bubble;
    double weight;  // normalised: members' weights sum to 1
  };
  std::vector<Member> members;
  int reach = 0;  // largest member reach
};

// The largest offset a preset bubble reaches along any axis at voxel size h,
// in voxels, without building it: the `reach` makeBubbleEstimator gives.
int bubbleReach(const BubbleSpec& spec, double h);

// Builds a preset bubble at voxel size h (world units per voxel).
BubbleEstimator makeBubbleEstimator(const BubbleSpec& spec, double h);

}  // namespace rockbake
