// Fold-over repair (docs/meshes.md, The repairs): removes fold-overs and
// zero-area triangles (mesh_defects.h's isDefective) from a closed,
// consistently oriented, edge-manifold triangle mesh, first by flipping
// edges, then by collapsing what flips cannot fix.
//
// A flip turns a triangle and its neighbour across an edge into the two
// triangles across the quad's other diagonal, when both new triangles have
// area and face the same side as the quad's surroundings, and the new edge
// does not exist yet. A collapse moves one end of an edge onto the other
// where the link condition holds and every triangle that moves keeps its
// area and its side; the two triangles on the edge go. Up to six rounds of
// flips (eight passes each, triangles in index order) and collapses.
//
// Gives: the mesh still closed and 2-manifold; no vertex moved; the vertices
// a collapse frees dropped (every per-vertex array with them, geometry/vertex_remap.h);
// normals recomputed. Returns the defects left (0 when clean). Deterministic.
// A per-vertex array neither empty nor vertex-sized: std::logic_error, before
// anything changes.
#pragma once

#include <cstddef>

#include "core/surface_mesh.h"

namespace rockbake {

std::size_t repairFoldOvers(SurfaceMesh& mesh);

}  // namespace rockbake
