// Cutting glued sheets apart (docs/meshes.md, The repairs): meshoptimizer
// does not check the link condition, so a collapse can glue two sheets
// together along an edge (more than one face each way) or pinch them together
// at a vertex. Each sheet then gets its own copies of the vertices there;
// nothing moves (the copies coincide with their originals).
//
// Where an undirected edge carries k faces each way (k > 1), each outgoing
// face is paired with an incoming one: its neighbour around the edge across
// the solid between the sheets when the faces alternate in direction around
// it, else the faces in angle order. The faces around each vertex are then
// grouped into fans joined through those pairs. Two pairs of one edge whose
// fans coincide at both its ends would still share the edge after the split
// (the sheets meet there and again elsewhere around both vertices):
// re-pairing them crosswise splits the fan at each end in two, one pair in
// each, so it is done until none is left. Every fan after the first of its
// vertex (in corner order) gets its own copy of the vertex.
//
// Every edge must be used as often each way (as collapsing a closed mesh
// leaves it); an edge that is not stays open. Deterministic. splitNonManifold
// throws std::logic_error, before anything changes, for a per-vertex array
// neither empty nor vertex-sized.
#pragma once

#include <cstddef>
#include <vector>

#include "core/surface_mesh.h"
#include "core/vec3.h"

namespace rockbake {

// On an index buffer (three indices a triangle) over `positions`: points the
// split fans' corners at the new vertices, numbered from positions.size() on,
// and returns, for each new vertex, the vertex it copies.
std::vector<unsigned int> splitPinches(std::vector<unsigned int>& indices, const std::vector<Vec3f>& positions);

// On a closed triangle mesh: the copies are appended with every per-vertex
// value of their originals (geometry/vertex_remap.h); normals recomputed. Returns
// the vertices added.
std::size_t splitNonManifold(SurfaceMesh& mesh);

}  // namespace rockbake
