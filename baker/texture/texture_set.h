// A texture set for an asset's LODs (docs/textures.md): each LOD unwrapped into an atlas of
// its own (uv_atlas.h), its tangent frames (tangents.h), its texels traced to the bake source
// (trace_texels.h), and its maps (bake_maps.h) written one at a time into `folder`
// (texture_files.h), at lodMapSize(params, k) texels (the colour maps at colourMapSize of
// that, from texels traced at their own size): LOD0's as <name>_BaseColor.png,
// <name>_Normal_LOD0.png, <name>_ORM.png, <name>_Height.exr and <name>_Mask.png, LOD k's as
// <name>_BaseColor_LOD<k>.png, <name>_Normal_LOD<k>.png, <name>_ORM_LOD<k>.png and
// <name>_Mask_LOD<k>.png (the height is LOD0's displacement alone). Each LOD's own atlas keeps
// the LOD chain's triangle budgets: a layout shared with LOD0 would have the simplifier keep
// LOD0's seams (docs/textures.md, "The LOD chain"). Occlusion is cast per LOD vertex
// (ambient_occlusion.h). Only `params.maps` are made. Deterministic: the files are
// byte-identical at any thread count. A large map (a hero's 4096² LOD0) is made and written
// in bands of rows, never whole, and LOD0's maps come last, once the ray scene is freed: the
// set's memory is the ray scene or a band, with the LOD's texel map and hits (docs/textures.md,
// "Memory").
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/surface_mesh.h"
#include "platform/phase_times.h"
#include "texture/texture_params.h"

namespace rockbake {

struct TextureSetRequest {
  TextureParams params;    // the preset's texture: block
  std::uint64_t seed = 0;  // the preset's seed: occlusion rays and the colour's noise
  // The grid's h, world units: the per-voxel colour variation's scale and the compact height's
  // step (h/256 rounded down to a power of two); 0: neither.
  double voxel_size = 0.0;
  bool varied = true;  // the rock's look (rock_look.h) on the palette; false: its colours exactly
  // The ground plane's z in the meshes' frame when the asset stands on it: its hidden surface is
  // packed small (uv_atlas.h) and the mask's alpha is its ground contact (bake_maps.h). None: a
  // free-standing rock, neither.
  std::optional<double> ground;
  std::string name;  // the asset's: file names <name>_BaseColor.png, …
  // The normal maps in DirectX's tangent space (green down, Unreal's) instead of OpenGL's (glTF's).
  bool directx_normals = false;
  std::filesystem::path folder;  // where the files go (created if missing)
  // Maps larger than kWholeMapSize are made and written in bands of this many rows, one band
  // in memory at a time (0: kBandRows); smaller ones whole. The files are the same either way.
  int band_rows = 0;
  int whole_map_size = 2048;  // the largest map made whole (≤ 0: every map in bands)
  // Called as the set goes: after every LOD's atlas (`lods_done` 0) and after each LOD's maps
  // (`lods_done` 1 … `lods`; `lod` the LOD just finished, `size` its maps' width). May be empty.
  std::function<void(int lod, int size, int lods_done, int lods)> progress;
};

inline constexpr int kBandRows = 512;

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
  std::vector<AssetMeshes> lods;    // the LODs with uvs and tangents, vertices split along seams
  std::vector<std::size_t> charts;  // per LOD
  // Per LOD: its maps' width and height, texels: the relief maps' (its colour maps' when it has
  // only those; `files` gives each map's).
  std::vector<int> sizes;
  std::vector<double> texels_per_unit;  // per LOD: texel density, texels per world unit
  std::vector<double> coverage;         // per LOD: the share of its maps its charts cover (uvCoverage)
  std::vector<TextureFile> files;       // LOD by LOD, LOD0 first, each LOD's in the order of params.maps
  std::size_t missed = 0;  // covered texels (of the LODs' sizes) whose rays found no source within the cage
  // Per step ("lod0 rays", "lod0 normal", …): wall-clock seconds and the process's CPU
  // seconds (all threads) over it.
  PhaseTimes steps;
};

// `lods`: LOD0 first, triangle meshes with normals, attributes and colours. `source`: the bake
// source (the refined surfaces before simplification, in the same frame). Throws
// std::invalid_argument on bad params, std::runtime_error on a failure to pack or write (the
// files written before it stay; the caller's folder is the unit of atomicity).
TextureSet bakeTextureSet(const std::vector<AssetMeshes>& lods, const AssetMeshes& source,
                          const TextureSetRequest& request);

// LOD `lod`'s file of `map` in `set`, or nullptr when none was made.
const TextureFile* findTextureFile(const TextureSet& set, int lod, TextureMap map);

}  // namespace rockbake
