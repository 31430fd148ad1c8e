// A texture set for an asset's LODs (docs/textures.md): each LOD's tangent frames
// (tangents.h), its texels traced to the bake source (trace_texels.h), and its maps
// (bake_maps.h) written one at a time into `folder` (texture_files.h): LOD0's as
// <name>_BaseColor.png, <name>_Normal_LOD0.png, <name>_ORM.png, <name>_Height.exr and
// <name>_Mask.png, and a normal map per further LOD k, <name>_Normal_LOD<k>.png. The LOD
// chain either shares LOD0's UV layout (the Megascans convention: the LODs were simplified
// from LOD0 after its atlas, seams kept, so one base colour, ORM and mask serve them all) or
// each LOD gets an atlas of its own (uv_atlas.h) and with it its own base colour, ORM and mask,
// named with "_LOD<k>" (the height is LOD0's displacement alone). Occlusion is cast once, on
// the source (ambient_occlusion.h). Only `params.maps` are made. Deterministic: the files
// are byte-identical at any thread count.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/surface_mesh.h"
#include "texture/texture_params.h"

namespace rockbake {

enum class LodLayout {
  SharedWithLod0,  // every LOD comes with uvs in LOD0's layout
  OwnAtlas,        // every LOD is unwrapped here, each into an atlas of its own
};

struct TextureFile {
  std::string file;  // relative to the folder
  TextureMap map;
  int lod = 0;
  int size = 0;  // texels across (and down)
  int channels = 0;
  int bits = 0;              // per channel: 8, 16 or 32 (float)
  std::string colour_space;  // "srgb" or "linear"
};

struct TextureSet {
  std::vector<AssetMeshes> lods;        // the LODs with uvs and tangents, vertices split along seams
  std::vector<std::size_t> charts;      // per LOD
  std::vector<double> texels_per_unit;  // per LOD: texel density, texels per world unit
  std::vector<TextureFile> files;       // in the order written
  std::size_t missed = 0;               // covered texels whose rays found no source within the cage
  // Per step ("lod0 rays", "lod0 normal", …): wall-clock seconds and the process's CPU
  // seconds (all threads) over it.
  struct Step {
    std::string name;
    double seconds = 0, cpu_seconds = 0;
  };
  std::vector<Step> steps;
};

// `lods`: LOD0 first, triangle meshes with normals, attributes and colours (and uvs, with
// SharedWithLod0). `source`: the bake source (the refined surfaces before simplification,
// in the same frame). Throws std::invalid_argument on bad params or a LOD without uvs where
// they are needed, std::runtime_error on a failure to pack or write (the files written
// before it stay; the caller's folder is the unit of atomicity).
TextureSet bakeTextureSet(const std::vector<AssetMeshes>& lods, const AssetMeshes& source, LodLayout layout,
                          const TextureParams& params, const std::string& name, const std::filesystem::path& folder);

}  // namespace rockbake
