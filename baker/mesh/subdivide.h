// Subdivision (docs/meshes.md): OpenSubdiv Far, Catmull-Clark on the quad-dominant
// extraction output (triangles and quads together), uniform refinement.
// Per-vertex primvars (durability, colluvium, curvature, altitude, and history when present) are refined
// with Far::PrimvarRefiner alongside the positions, so each refined value is a
// convex combination of the input values and stays within their range.
// Edges where a face lying on the ground plane (every vertex at z = 0) meets
// one that does not are infinitely sharp creases: a ground cap stays flat on
// z = 0 and its rim stays on the ground.
#pragma once

#include "core/surface_mesh.h"

namespace rockbake {

struct SubdivideParams {
  int levels = 2;  // 0..3; 0 only triangulates
};

// Returns a triangle-only mesh (each refined quad split along its shorter
// diagonal) with area-weighted unit vertex normals. Of the per-vertex arrays
// (core/surface_mesh.h), positions, the four baked attributes and the history are refined;
// colours are dropped (apply the palette afterwards), as is any array added
// after them. An empty mesh stays empty.
// Throws std::invalid_argument if levels is outside 0..3 or the mesh is not a
// valid closed manifold OpenSubdiv accepts.
SurfaceMesh subdivideSurface(const SurfaceMesh& mesh, const SubdivideParams& params);

// Vertex count after `levels` uniform Catmull-Clark refinements of a closed
// mesh with the given counts (V + E + F per level).
std::size_t catmullClarkVertexCount(std::size_t vertices, std::size_t triangles, std::size_t quads, int levels);

// Recomputes `normals` as area-weighted averages of the triangles' normals.
void computeVertexNormals(SurfaceMesh& mesh);

}  // namespace rockbake
