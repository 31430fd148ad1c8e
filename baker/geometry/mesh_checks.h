// Checks every stage applies to meshes (docs/meshes.md): closed and consistently
// oriented, the enclosed volume, bounds. Plain functions over core/surface_mesh.h,
// built on the mesh kernel (geometry/edge_table.h, geometry/triangle_geometry.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

// An edge not shared by exactly two faces of opposite orientation.
struct OpenEdge {
  std::uint32_t a, b;  // vertex indices, a < b
  int uses;            // how many faces use the edge (either direction)
};

// Every open edge of the faces (triangles, and the quads of a SurfaceMesh):
// empty for a closed, consistently oriented 2-manifold.
std::vector<OpenEdge> findOpenEdges(const TriangleMesh& mesh);
std::vector<OpenEdge> findOpenEdges(const SurfaceMesh& mesh);

// Signed volume enclosed by the faces, in cubed position units (positive when
// they face outwards).
double signedVolume(const TriangleMesh& mesh);
double signedVolume(const SurfaceMesh& mesh);

// Sets meshes.bounds_min/max to the box around both surfaces' vertices
// (zero when both are empty).
void updateBounds(AssetMeshes& meshes);

}  // namespace rockbake
