// Relaxing what the fold-over repair leaves (docs/meshes.md, The LOD chain
// and its budgets), on a mesh with no error bound to keep (a LOD simplified to
// a triangle budget): moves vertices, never topology.
//
// Takes a closed, consistently oriented, edge-manifold triangle mesh. Each
// vertex of a defective triangle (mesh_defects.h's isDefective), in index
// order, goes to the mean of its neighbours (or halfway, or a quarter of the
// way), or else halfway or a quarter of the way towards one neighbour, the
// first that leaves fewer defective triangles among those the move can
// change; up to ten rounds. Gives the mesh with faces and every per-vertex
// array but positions and normals as they were; normals recomputed. Returns
// the defects left. Deterministic.
#pragma once

#include <cstddef>

#include "core/surface_mesh.h"

namespace rockbake {

std::size_t relaxFoldOvers(SurfaceMesh& mesh);

}  // namespace rockbake
