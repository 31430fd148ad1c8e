// A texture set for an asset's LODs (docs/textures.md): for each LOD, its own UV atlas
// (uv_atlas.h) and tangent frames (tangents.h), its texels traced to the bake source
// (trace_texels.h), and its maps (bake_maps.h) written one at a time into `folder`
// (texture_files.h): LOD0's as <name>_BaseColor.png, <name>_Normal_LOD0.png, <name>_ORM.png,
// <name>_Height.exr and <name>_Mask.png; a further LOD k's normal map as
// <name>_Normal_LOD<k>.png and, its atlas being its own, its other maps with "_LOD<k>" (no
// height: that is LOD0's displacement). Occlusion is cast once, on the source
// (ambient_occlusion.h). Only `params.maps` are made. Deterministic: the files are
// byte-identical at any thread count.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/surface_mesh.h"
#include "texture/texture_params.h"

namespace rockbake {

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
  std::vector<AssetMeshes> lods;                        // the LODs with uvs and tangents, vertices split along seams
  std::vector<std::size_t> charts;                      // per LOD
  std::vector<double> texels_per_unit;                  // per LOD: texel density, texels per world unit
  std::vector<TextureFile> files;                       // in the order written
  std::size_t missed = 0;                               // covered texels whose rays found no source within the cage
  std::vector<std::pair<std::string, double>> seconds;  // per step ("atlas", "occlusion", "lod0 normal", …)
};

// `lods`: LOD0 first, triangle meshes with normals, attributes and colours. `source`: the
// bake source (the refined surfaces before simplification, in the same frame). Throws
// std::invalid_argument on bad params and std::runtime_error on a failure to pack or write
// (the files written before it stay; the caller's folder is the unit of atomicity).
TextureSet bakeTextureSet(const std::vector<AssetMeshes>& lods, const AssetMeshes& source, const TextureParams& params,
                          const std::string& name, const std::filesystem::path& folder);

}  // namespace rockbake
