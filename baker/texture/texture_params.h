// The texture stage (docs/textures.md): UV atlases, MikkTSpace tangent frames and maps baked
// by ray casts from every LOD to the bake source (the finest surface: extraction, subdivision
// and detail, before simplification), written as a Megascans-style texture set. Its
// parameters are the preset's `texture:` block, TextureParams (preset/preset.h); this header
// holds what the stage asks of them. Each operation has its own header:
//   uv_atlas.h       charts, LSCM, packing: a mesh split along seams with uvs
//   tangents.h       per-vertex tangent frames (MikkTSpace convention, glTF TANGENT)
//   rasterize_uv.h   which triangle covers each texel centre; dilate_texels.h: gutter fill
//   ray_source.h     the bake source as a ray-cast scene (Embree 3)
//   ambient_occlusion.h, trace_texels.h, bake_maps.h: occlusion, hits, maps
//   texture_files.h  PNG and EXR files, named in the Megascans manner
//   texture_set.h    all of it for an asset's LODs
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "preset/preset.h"

namespace rockbake {

// Thrown when an atlas's charts fit its map at no density: the map is too small for the
// gutters (texture.size against texture.padding), which the caller reports as bad input.
class ChartsDoNotFit : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws std::invalid_argument naming the first field outside the range the preset's reader
// allows (docs/preset-reference.md), for callers that fill TextureParams themselves.
void checkTextureParams(const TextureParams& params);

// Whether `params.maps` lists `map`.
bool wantsMap(const TextureParams& params, TextureMap map);

// "base_color", "normal", "orm", "height", "mask": the preset's names.
std::string mapName(TextureMap map);

// The width and height of LOD `lod`'s maps, texels: `params.size` for LOD0 and, with
// LodMapSize::Halved, size / 2^lod for the others, at least 256 (or size, when it is smaller);
// with LodMapSize::Full, `params.size` for every LOD.
int lodMapSize(const TextureParams& params, int lod);

// Whether `map` is a colour map (base colour, ORM, mask, History), sized by colourMapSize, or a
// relief map (normal, height), at the LOD's size.
bool isColourMap(TextureMap map);

// The width and height of a LOD's colour maps, texels: `size` (the LOD's) halved while the half
// keeps at least `params.colour_density` texels a voxel and at least min(size, 256) texels
// across; `texels_per_voxel` is the LOD's density at `size`. `size` when colour_density is 0 or
// texels_per_voxel is not positive.
int colourMapSize(const TextureParams& params, int size, double texels_per_voxel);

// Texels a map may spend per triangle of the bake source (the finest surface): 8 × 8. Beyond
// that a map holds nothing the surface can give it (a 126-triangle rock baked at 8192 spends
// half a million texels per triangle), only time and memory.
inline constexpr double kUsefulTexelsPerSourceTriangle = 64.0;

// The largest map size worth baking from a source of `source_triangles` triangles: the power
// of two at least sqrt(source_triangles · kUsefulTexelsPerSourceTriangle), at least 256. The
// texture set bakes each LOD at min(lodMapSize, this).
int usefulMapSize(std::size_t source_triangles);

}  // namespace rockbake
