// Binary PLY export of one surface (docs/meshes.md), written atomically.
//
//   format binary_little_endian 1.0
//   element vertex: float x y z nx ny nz, uchar red green blue,
//                   float durability colluvium curvature
//   element face:   list uchar uint vertex_indices (triangles, CCW from outside)
// Positions in world units, z up. Colours are the mesh's linear colours
// encoded to 8-bit sRGB (what PLY viewers display).
#pragma once

#include <filesystem>

#include "core/surface_mesh.h"

namespace rockbake {

// Throws std::runtime_error on failure. The mesh must be triangle-only with
// normals, colours and attributes for every vertex.
void writePly(const SurfaceMesh& mesh, const std::filesystem::path& file);

}  // namespace rockbake
