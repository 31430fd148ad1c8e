// asset.json (docs/rendering.md): what a studio's asset browser reads, in the spirit of a
// Megascans payload, written beside manifest.json:
//
//   {"rockbake_asset": 1, "name", "tags": [..],
//    "units_per_meter", "size_m": [x, y, z],              // the bounding box in metres
//    "delivery": {"profile", "normal_map": "opengl" | "directx", "images": "files" | "embedded"},
//                                                          // textures/' normal maps, the GLBs' images
//    "pivot": "footprint-centre-on-ground", "up_axis": "z" (PLY, VDB) / "y" (GLB, OBJ),
//    "lods": [{"level", "file", "triangles", "vertices"}, ..],   // level 0 first; both surfaces counted
//    with a texture set (docs/textures.md), each LOD also "map_size" (texels) and
//    "texel_density" (pixels per metre), and
//    "maps": [{"type", "lod", "file", "size": [w, h], "colour_space", "channels", "bits"}, ..],
//    "average_color": {"srgb": "#rrggbb", "linear": [r, g, b]},  // area-weighted over LOD0
//    "preview": "render.png" | null, "movie": "turntable.mp4" | null,
//    "collision": {"file": "collision.glb", "naming": "unreal" | "godot", "hull_count", "vertex_count",
//                  "hulls": [{"node", "vertices", "volume_m3"}, ..]},   // only when export lists collision
//    "clasts": {"stones", "shapes", "voxel_size_m", "size_m": [smallest, largest],
//               "lods": [{"level", "stones", "triangles"}, ..], "maps": [{"type", "file", "size"}, ..]},
//                                                                // stones on the apron; only with some
//    "ground": {"pivot": "ground-contact", "sink_m", "suggested_burial_m",
//               "footprint_m": [[x, y], ..], "rock_footprint_m": [[x, y], ..], "contact_area_m2"},
//                                                                // where it meets the ground; only with ground
//    "sets": {"full": {"download_bytes", "gpu_bytes", "gpu_texture_bytes", "gpu_mesh_bytes"},
//             "compressed": {"folder": "compressed", ..the same}},   // only with delivery.compressed
//                                                                // (compress/compressed_set.h, docs/delivery.md)
//    "individual": {..}                                          // what the seed drew from the family
//                                                                // (pipeline/individual_json.h); only with one
//    "input_hash"}
//
// Everything in it is a function of the bake's inputs (no times, no host).
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/clast_set.h"
#include "core/surface_mesh.h"
#include "core/voxel_rock.h"

namespace rockbake {

inline constexpr const char* kAssetFile = "asset.json";

// One convex hull of collision.glb (docs/collision.md).
struct AssetHull {
  std::string node;  // its node's (and mesh's) name
  std::size_t vertices = 0;
  double volume = 0.0;  // world units³
};

// collision.glb: its hulls in the file's node order.
struct AssetCollision {
  std::string file;    // relative to the asset folder
  std::string naming;  // the preset's collision.naming: "unreal" or "godot"
  std::vector<AssetHull> hulls;
};

struct AssetLod {
  std::string file;  // relative to the asset folder
  const AssetMeshes* meshes = nullptr;
  int map_size = 0;            // its maps' width and height, texels; 0: no texture set
  double texels_per_unit = 0;  // its atlas's texel density, texels per world unit
};

// One file of the texture set.
struct AssetMap {
  std::string type;  // "base_color", "normal", "orm", "height", "mask"
  int lod = 0;
  std::string file;          // relative to the asset folder
  int size = 0;              // width and height, texels
  std::string colour_space;  // "srgb" or "linear"
  std::string channels;      // "RGB", "RGBA" or "Y"
  int bits = 0;              // per channel: 8, 16, or 32 (float)
};

struct AssetDescription {
  std::string name;
  std::vector<std::string> tags;
  double units_per_meter = 1.0;
  std::vector<AssetLod> lods;  // level 0 first
  std::vector<AssetMap> maps;  // empty: no texture set
  std::string preview;         // relative path, empty: none
  std::string movie;           // the turntable movie, relative path, empty: none
  std::string input_hash;
  std::optional<AssetCollision> collision;  // none: export does not list collision
  nlohmann::ordered_json individual;        // null: the preset has no family
  nlohmann::ordered_json clasts;            // null: no stones (clastsJson)
  nlohmann::ordered_json ground;            // null: no ground (groundJson)
  nlohmann::ordered_json delivery;          // null: not given (pipeline/delivery_profile.h)
  nlohmann::ordered_json sets;              // null: no compressed set (compress/compressed_set.h)
};

// asset.json's "ground": the rock (and apron) where they meet the ground plane, after sinking
// `sink` (world units): the convex footprints of the solid voxels in the layer at the ground plane,
// about `pivot` (footprintPivot), in metres, counter-clockwise from the lowest-x point; the
// contact's area; the suggested burial depth. Null without ground.
nlohmann::ordered_json groundJson(const VoxelRock& rock, const std::array<double, 3>& pivot, double sink,
                                  double units_per_meter);

// asset.json's "clasts" for `set` on a grid of voxel size `h` (world units); null without stones.
nlohmann::ordered_json clastsJson(const ClastSet& set, double h, double units_per_meter);

// Area-weighted mean of the vertex colours (linear RGB) over both surfaces.
std::array<double, 3> averageColor(const AssetMeshes& meshes);

nlohmann::ordered_json assetJson(const AssetDescription& asset);

// Writes <asset_dir>/asset.json atomically.
void writeAssetJson(const AssetDescription& asset, const std::filesystem::path& asset_dir);

}  // namespace rockbake
