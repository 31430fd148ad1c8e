// The export stage takes AssetMeshes (and the VoxelRock) and gives files:
// glb_file.h, ply_file.h, obj_file.h, vdb_file.h, each written atomically.
//
// Binary glTF 2.0 export (SPEC §3) via tinygltf, written atomically.
//
// One mesh and one node per non-empty surface (named "rock", "colluvium"),
// triangles with POSITION, NORMAL, COLOR_0 (linear RGB float, as glTF
// requires), and float scalars _DURABILITY, _COLLUVIUM, _CURVATURE, _ALTITUDE.
// glTF is y-up: the asset's z-up world (x, y, z) is written as (x, z, -y),
// in the same units (metres to glTF readers).
#pragma once

#include <filesystem>

#include "core/surface_mesh.h"

namespace rockbake {

// Throws std::runtime_error on failure.
void writeGlb(const AssetMeshes& meshes, const std::filesystem::path& file);

}  // namespace rockbake
