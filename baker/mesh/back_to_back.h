// Back-to-back pairs (docs/meshes.md, The repairs): collapsing a thin part
// can leave two coincident triangles of opposite winding glued back to back
// (each of their edges then has four faces). Removing both restores
// edge-manifoldness; the surface is pinched there, as the collapse intended.
//
// Takes a triangle index buffer (three indices a triangle, meshoptimizer's).
// Within each set of triangles on the same three vertices, each triangle is
// paired with the next one of opposite winding, and every pair is removed (a
// triangle left without a partner stays): dropping two of the same winding
// would leave their edges with more faces one way than the other. The other
// triangles keep their order. Returns the vertices of the removed pairs, three
// a pair. Deterministic (a parallel sort of unique keys).
#pragma once

#include <vector>

namespace rockbake {

std::vector<unsigned int> dropBackToBackPairs(std::vector<unsigned int>& indices);

}  // namespace rockbake
