// Merging parts into near-convex pieces (docs/collision.md, "Merging"), in the
// spirit of hierarchical approximate convex decomposition (Mamou and Ghorbel,
// "A simple and efficient approach for 3D mesh approximate convex
// decomposition", ICIP 2009): parts are the nodes of a graph whose edges join
// parts that touch; the edge whose merge costs least is collapsed, again and
// again. Here the cost is the air the joint hull adds,
//   air(hull(A ∪ B)) − air(hull(A)) − air(hull(B)),
// air(H) being the air voxels whose centres H holds (air_count.h): the
// material of other parts inside a hull costs nothing, so a piece may wrap
// around another.
// Merging goes on while more than `max_pieces` are left. Below that, merges
// go on (cheapest first) while together they add at most `free_fraction` of
// all the voxels in air, counted on the hulls as the vertex cap will leave
// them (reduce_hull.h, `max_vertices`: one hull of a round boulder claims
// much more air than two would); a merge the cap makes too dear is passed
// over, and merging stops at the first that costs more than what is left
// before the cap. Where no touching pair is left and there
// are still too many pieces, the nearest pieces (by bounding-box gap) are
// joined too. Hulls in the parts' frame (voxel index space).
// Deterministic whatever the thread count: ties go to the lower part numbers.
#pragma once

#include <cstddef>
#include <vector>

#include "collision/air_count.h"
#include "collision/point_hull.h"
#include "collision/voxel_parts.h"

namespace rockbake {

struct MergeParams {
  std::size_t max_pieces = 16;  // >= 1
  double free_fraction = 0.0;   // below max_pieces, merges may add this × all the voxels in air, together
  int max_vertices = 64;        // the vertex cap the free merges are judged with
};

struct MergedPiece {
  PointHull hull;          // of all its parts' voxels
  std::size_t voxels = 0;  // its parts' voxels
};

// The pieces, at most max_pieces of them (none for no parts), in the order
// they were formed (first surviving part first).
// `air` counts the air of the grid the parts came from.
std::vector<MergedPiece> mergeParts(const VoxelParts& parts, const AirCounter& air, const MergeParams& params);

}  // namespace rockbake
