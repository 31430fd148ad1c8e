// The texture stage (docs/textures.md): UV atlases, MikkTSpace tangent frames and maps baked
// by ray casts from every LOD to the bake source (the finest surface: extraction, subdivision
// and detail, before simplification), written as a Megascans-style texture set. This header
// holds the stage's parameters; each operation has its own header:
//   uv_atlas.h       charts, LSCM, packing: a mesh split along seams with uvs
//   tangents.h       per-vertex tangent frames (MikkTSpace convention, glTF TANGENT)
//   rasterize_uv.h   which triangle covers each texel centre; dilate_texels.h: gutter fill
//   ray_source.h     the bake source as a ray-cast scene (Embree 3)
//   ambient_occlusion.h, trace_texels.h, bake_maps.h: occlusion, hits, maps
//   texture_files.h  PNG and EXR files, named in the Megascans manner
//   texture_set.h    all of it for an asset's LODs
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rockbake {

enum class TextureMap {
  BaseColor,  // <name>_BaseColor.png: 8-bit sRGB RGB
  Normal,     // <name>_Normal_LOD<k>.png: 16-bit RGB, tangent space, OpenGL convention (+Y up)
  Orm,        // <name>_ORM.png: 8-bit linear RGB, R occlusion, G roughness, B metal (0)
  Height,     // <name>_Height.exr: 32-bit float, signed distance LOD0 → source along LOD0's normal, world units
  Mask,       // <name>_Mask.png: 8-bit linear RGBA, durability, colluvium, curvature, altitude (as COLOR_1)
};

struct TextureParams {
  int size = 2048;   // map width and height, texels: a power of two, 256..8192
  int padding = 8;   // empty texels between charts, 0..64; every map is dilated into them
  int ao_rays = 32;  // ambient-occlusion rays per bake-source vertex, 1..1024
  // How far an occlusion ray looks, world units; 0: without limit (the whole asset occludes).
  double ao_distance = 0.0;
  // How far each texel's ray looks from the LOD's surface, both ways along its normal,
  // world units; 0: 5 % of the bake source's bounding-box diagonal.
  double cage = 0.0;
  std::vector<TextureMap> maps = {TextureMap::BaseColor, TextureMap::Normal, TextureMap::Orm, TextureMap::Height,
                                  TextureMap::Mask};
  std::uint64_t seed = 0;   // the preset's seed: occlusion rays and the colour's grain
  double voxel_size = 0.0;  // the grid's h, world units: the scale of the per-voxel colour variation; 0: none
};

// Throws std::invalid_argument naming the first field outside its range.
void checkTextureParams(const TextureParams& params);

// Whether `params.maps` lists `map`.
bool wantsMap(const TextureParams& params, TextureMap map);

// "base_color", "normal", "orm", "height", "mask".
std::string mapName(TextureMap map);

}  // namespace rockbake
