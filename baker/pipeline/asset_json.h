// asset.json (docs/rendering.md): what a studio's asset browser reads, in the spirit of a
// Megascans payload, written beside manifest.json:
//
//   {"rockbake_asset": 1, "name", "tags": [..],
//    "units_per_meter", "size_m": [x, y, z],              // the bounding box in metres
//    "pivot": "footprint-centre-on-ground", "up_axis": "z" (PLY, VDB) / "y" (GLB, OBJ),
//    "lods": [{"level", "file", "triangles", "vertices"}, ..],   // level 0 first; both surfaces counted
//    "average_color": {"srgb": "#rrggbb", "linear": [r, g, b]},  // area-weighted over LOD0
//    "preview": "render.png" | null, "movie": "turntable.mp4" | null, "input_hash"}
//
// Everything in it is a function of the bake's inputs (no times, no host).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/surface_mesh.h"

namespace rockbake {

inline constexpr const char* kAssetFile = "asset.json";

struct AssetLod {
  std::string file;  // relative to the asset folder
  const AssetMeshes* meshes = nullptr;
};

struct AssetDescription {
  std::string name;
  std::vector<std::string> tags;
  double units_per_meter = 1.0;
  std::vector<AssetLod> lods;  // level 0 first
  std::string preview;         // relative path, empty: none
  std::string movie;           // the turntable movie, relative path, empty: none
  std::string input_hash;
};

// Area-weighted mean of the vertex colours (linear RGB) over both surfaces.
std::array<double, 3> averageColor(const AssetMeshes& meshes);

nlohmann::ordered_json assetJson(const AssetDescription& asset);

// Writes <asset_dir>/asset.json atomically.
void writeAssetJson(const AssetDescription& asset, const std::filesystem::path& asset_dir);

}  // namespace rockbake
