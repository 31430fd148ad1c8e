#include "texture/texture_params.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "preset/schema.h"

namespace rockbake {

void checkTextureParams(const TextureParams& p) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("texture." + what); };
  if (p.size < 256 || p.size > 8192 || (p.size & (p.size - 1)) != 0)
    fail("size: " + std::to_string(p.size) + " is not a power of two from 256 to 8192");
  if (p.padding < 0 || p.padding > 64) fail("padding: " + std::to_string(p.padding) + " is outside 0..64 texels");
  if (p.ao_rays < 1 || p.ao_rays > 1024) fail("ao_rays: " + std::to_string(p.ao_rays) + " is outside 1..1024");
  if (!(p.ao_distance >= 0) || !std::isfinite(p.ao_distance)) fail("ao_distance: must be 0 or a positive length");
  if (!(p.cage >= 0) || !std::isfinite(p.cage)) fail("cage: must be 0 or a positive length");
  if (!(p.colour_density >= 0 && p.colour_density <= 64))
    fail("colour_density: " + std::to_string(p.colour_density) + " is outside 0..64 texels a voxel");
  if (p.maps.empty()) fail("maps: lists no map");
}

bool wantsMap(const TextureParams& params, TextureMap map) {
  return std::find(params.maps.begin(), params.maps.end(), map) != params.maps.end();
}

std::string mapName(TextureMap map) {
  // The History map is a look's, never listed in texture.maps, so the schema does not name it.
  return map == TextureMap::History ? "history" : schema::nameOf(map);
}

int lodMapSize(const TextureParams& params, int lod) {
  if (params.lod_size == LodMapSize::Full || lod <= 0) return params.size;
  return std::max(params.size >> std::min(lod, 30), std::min(params.size, 256));
}

bool isColourMap(TextureMap map) {
  return map != TextureMap::Normal && map != TextureMap::Height;
}

int colourMapSize(const TextureParams& params, int size, double texels_per_voxel) {
  if (!(params.colour_density > 0) || !(texels_per_voxel > 0)) return size;
  const int floor = std::min(size, 256);
  int colour = size;
  while (colour / 2 >= floor && texels_per_voxel * (colour / 2) / size >= params.colour_density) colour /= 2;
  return colour;
}

int usefulMapSize(std::size_t source_triangles) {
  const double wanted = std::sqrt(double(source_triangles) * kUsefulTexelsPerSourceTriangle);
  int size = 256;
  while (size < wanted && size < 8192) size *= 2;
  return size;
}

}  // namespace rockbake
