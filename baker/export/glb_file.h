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
// glTF is y-up: the asset's z-up world (x, y, z) is written as (x, z, -y), in metres
// (glTF's unit): world units times GlbConventions::meters_per_unit.
//
// Textured (docs/textures.md): a surface with uvs and tangents also gets
// TEXCOORD_0 and TANGENT (xyzw, handedness in w: the frames the maps were
// baked in), and its material (one per surface, named after it) the texture
// set's maps by relative URI (or embedded, GlbConventions::embed_images): baseColorTexture, normalTexture,
// occlusionTexture and metallicRoughnessTexture (the one ORM image: R
// occlusion, G roughness, B metal), trilinear, clamped at the edges. With a
// base-colour map COLOR_0 is white: glTF multiplies it into the map (and
// COLOR_1, the mask, is valid only beside a COLOR_0).
#pragma once

#include <filesystem>
#include <string>

#include "core/clast_set.h"
#include "core/surface_mesh.h"

namespace rockbake {

// How an asset's GLBs name what they hold, and in what unit (docs/delivery.md: the delivery
// profile's conventions). The defaults name meshes as before any profile: "rock_lod0".
struct GlbConventions {
  std::string mesh_prefix;       // before every mesh and node name: "SM_goblin_" gives "SM_goblin_rock_lod0"
  std::string material_prefix;   // before every material name: "goblin_" gives "goblin_rock", "goblin_clast"
  double meters_per_unit = 1.0;  // positions, translations and stone scales are multiplied by it, > 0
  bool embed_images = false;     // the maps' bytes in the GLB's buffer, not URIs beside it
  // The normal maps' files are DirectX's (green down): an embedded one is stored with its green
  // turned back (8-bit), since glTF reads OpenGL's. URIs must not name such files.
  bool directx_normal_files = false;
  std::filesystem::path image_folder;  // what the maps' URIs are relative to (the asset folder): read to embed
};

// The name of `surface`'s ("rock", "colluvium", "clast_3", "clast_shape_0") mesh and node in
// LOD `lod`'s file: "rock_lod0" (a stone's and a stone shape's, `lod` < 0: no LOD suffix), after
// the conventions' prefix. Engines pair other files' nodes with it (collision_glb.h).
std::string glbMeshName(const std::string& surface, int lod, const std::string& prefix = {});

// A LOD's maps, as URIs relative to the file that names them ("textures/goblin_ORM.png");
// empty: that map is not there. Both surfaces share them (one atlas).
struct MaterialMaps {
  std::string base_color;  // 8-bit sRGB
  std::string normal;      // tangent space, OpenGL convention (+Y)
  std::string orm;         // linear: R occlusion, G roughness, B metal
  std::string height;      // film displacement, world units (the OBJ's MTL names it)
  bool empty() const { return base_color.empty() && normal.empty() && orm.empty() && height.empty(); }
};

// Stones (core/clast_set.h): LOD `lod` keeps clasts->lod_counts[lod] of them, each a node
// "clast_<k>" (k its index among the stones, largest first) with a translation, rotation and
// uniform scale, instancing one of the meshes "clast_shape_<s>" (only those used), which share the
// material "clast" (the stones' own maps, "textures/<file>", when they have them).
// Throws std::runtime_error on failure.
// `lod` names the nodes and meshes: rock_lod0, colluvium_lod0, … (so LODs
// imported into one scene keep their names). `maps`: the LOD's texture set
// (the meshes must then have uvs and tangents).
void writeGlb(const AssetMeshes& meshes, const std::filesystem::path& file, int lod = 0, const MaterialMaps& maps = {},
              const ClastSet* clasts = nullptr, const GlbConventions& conventions = {});

}  // namespace rockbake
