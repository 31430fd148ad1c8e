// Fewer vertices for a convex hull, keeping all of it inside (docs/collision.md,
// "Vertex cap"): the result is the intersection of a chosen few of the hull's
// supporting half-spaces, each of which holds the whole hull, so the result
// holds it too. It starts from the hull's bounding box and adds, one at a
// time, the facet plane that cuts the most volume off it, as long as its
// vertices stay within the cap (Qhull's half-space intersection gives them;
// a plane that would break the cap is passed over for the next). A hull
// already within the cap is returned as it is. Deterministic. Throws
// std::runtime_error when Qhull fails.
#pragma once

#include <vector>

#include "collision/point_hull.h"

namespace rockbake {

struct CappedHull {
  std::vector<Vec3d> vertices;    // at most the cap
  std::vector<HullPlane> planes;  // the half-spaces it is the intersection of
};

// `max_vertices` >= 8.
CappedHull reduceHull(const PointHull& hull, int max_vertices);

}  // namespace rockbake
