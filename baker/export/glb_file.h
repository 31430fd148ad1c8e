// The export stage takes AssetMeshes (and the VoxelRock) and gives files:
// glb_file.h, ply_file.h, obj_file.h, vdb_file.h, each written atomically.
//
// Binary glTF 2.0 export (docs/meshes.md) via tinygltf, written atomically.
//
// One mesh and one node per non-empty surface (named "rock_lodN",
// "colluvium_lodN"), triangles with POSITION, NORMAL, COLOR_0 (linear RGB
// float, as glTF requires), float scalars _DURABILITY, _COLLUVIUM, _CURVATURE,
// _ALTITUDE, and the same four packed into COLOR_1 (RGBA float, each 0..1:
// durability normalised over AssetMeshes::durability_range (0 on the colluvium
// surface), colluvium coverage, calibrated curvature s, altitude), for
// importers that drop custom attributes.
// glTF is y-up: the asset's z-up world (x, y, z) is written as (x, z, -y),
// in the same units (metres to glTF readers).
#pragma once

#include <filesystem>
#include <string>

#include "core/surface_mesh.h"

namespace rockbake {

// The name of `surface`'s ("rock", "colluvium") mesh and node in LOD `lod`'s file:
// "rock_lod0". Engines pair other files' nodes with it (collision_glb.h).
std::string glbMeshName(const std::string& surface, int lod);

// Throws std::runtime_error on failure.
// `lod` names the nodes and meshes: rock_lod0, colluvium_lod0, … (so LODs
// imported into one scene keep their names).
void writeGlb(const AssetMeshes& meshes, const std::filesystem::path& file, int lod = 0);

}  // namespace rockbake
