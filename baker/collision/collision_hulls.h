// The collision stage (docs/collision.md): takes the weathered VoxelRock and
// CollisionParams, gives the convex hulls a game engine collides with, as plain
// data for the export stage (collision.glb). No I/O.
//
// Each material (the rock; the colluvium on request, separately) is cut into
// small parts from its voxels (voxel_parts.h), the parts are merged into at
// most `max_hulls` near-convex pieces (merge_parts.h), each piece is hulled
// with Qhull (point_hull.h) and its hull cut down to at most `max_vertices`
// vertices while it still holds the whole piece (reduce_hull.h). Every voxel
// cube of the material lies inside a hull. Positions are world units in the
// simulation's frame (z up, the ground at z = 0; not about the pivot: the
// export stage moves them). Deterministic: the same rock gives the same hulls,
// bit for bit, whatever the thread count.
//
// Throws std::invalid_argument for parameters outside their ranges
// (preset/preset.h, CollisionParams) and std::runtime_error if Qhull fails.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

struct ConvexHull {
  std::vector<Vec3d> positions;                         // world units
  std::vector<std::array<std::uint32_t, 3>> triangles;  // closed, counter-clockwise seen from outside
  double volume = 0.0;                                  // world units³
  std::size_t voxels = 0;                               // voxels of the piece it holds
};

struct CollisionHulls {
  std::vector<ConvexHull> rock;       // largest first
  std::vector<ConvexHull> colluvium;  // largest first; empty unless CollisionParams::colluvium
  // With CollisionParams::colluvium, the stones on the apron (docs/model.md §13), stone k's hull
  // at k, the largest max_hulls of them (added by the caller: stoneHull).
  std::vector<ConvexHull> stones;
};

CollisionHulls buildCollisionHulls(const VoxelRock& rock, const CollisionParams& params);

// The convex hull of one stone's points (world units), its vertices capped at max_vertices the
// way the voxels' hulls are (reduce_hull.h: it still holds every point).
ConvexHull stoneHull(const std::vector<Vec3d>& points, int max_vertices);

// The hulls of one material's voxels (none when it has none), largest first.
std::vector<ConvexHull> hullVoxels(const VoxelRock& rock, Material material, const CollisionParams& params);

}  // namespace rockbake
