// Speck removal (docs/meshes.md, The LOD chain and its budgets): at a LOD's
// budget, a speck of debris (a lone colluvium voxel) simplifies to a handful
// of triangles lying flat on each other, which no flip or move can open again.
//
// Takes a closed triangle mesh. Removes every connected piece (triangles
// joined through shared vertices) of at most `max_triangles` triangles that
// holds a defective triangle (mesh_defects.h's isDefective), with its
// vertices and their values in every per-vertex array (geometry/vertex_remap.h);
// the rest is kept in order, and the mesh stays closed. Normals recomputed
// when anything went. Returns the triangles removed. Deterministic. A
// per-vertex array neither empty nor vertex-sized: std::logic_error, before
// anything changes.
#pragma once

#include <cstddef>

#include "core/surface_mesh.h"

namespace rockbake {

std::size_t dropCollapsedSpecks(SurfaceMesh& mesh, std::size_t max_triangles);

}  // namespace rockbake
