// Texture files (docs/textures.md), named in the Megascans manner and written atomically
// (platform/atomic_file.h): the bytes depend on the pixels alone (no time stamps).
//   <name>_BaseColor.png       8-bit sRGB RGB (an sRGB chunk says so)
//   <name>_Normal_LOD<k>.png   8-bit RGB, linear (16-bit with texture.precision: full)
//   <name>_ORM.png             8-bit RGB, linear (no colour chunk: data, not colour)
//   <name>_Mask.png            8-bit RGBA, linear
//   <name>_Height.exr          16-bit half float (32-bit with texture.precision: full), one channel
//                              "Y", ZIP-compressed, world units
// PNGs are compressed for speed, in parallel bands (png_encoder.h); any PNG reader reads them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "texture/bake_maps.h"
#include "texture/texture_params.h"

namespace rockbake {

// "<name>_BaseColor.png", "<name>_Normal_LOD<lod>.png", …; `lod` >= 0 adds "_LOD<lod>" to a
// map that is not a normal map too (a LOD with an atlas of its own), and a normal map without
// it is LOD0's.
std::string textureFileName(const std::string& name, TextureMap map, int lod = -1);

// 8-bit, 3 or 4 channels; `srgb`: the values are sRGB-encoded colour. Throws
// std::runtime_error naming the file on failure (nothing is left half-written).
void writeTexturePng(const std::filesystem::path& file, const TextureImage<std::uint8_t>& image, bool srgb);
// 16-bit, 3 channels, linear.
void writeTexturePng(const std::filesystem::path& file, const TextureImage<std::uint16_t>& image);
// 1 channel, stored as 32-bit float, or as 16-bit half float where `half` (OpenEXR rounds each value).
void writeTextureExr(const std::filesystem::path& file, const TextureImage<float>& image, bool half = false);

// A map made band by band: bands(first_row, last_row) returns the image of those rows
// (TextureImage::first_row = first_row). The writers below ask for the bands of
// `band_rows` rows in order (the last one shorter where band_rows does not divide the size),
// hold one at a time, and write the same bytes as the whole map's writers above.
template <class T>
using TextureBands = std::function<TextureImage<T>(int first_row, int last_row)>;
void writeTexturePng(const std::filesystem::path& file, int size, int channels, bool srgb, int band_rows,
                     const TextureBands<std::uint8_t>& bands);
void writeTexturePng(const std::filesystem::path& file, int size, int band_rows,
                     const TextureBands<std::uint16_t>& bands);
void writeTextureExr(const std::filesystem::path& file, int size, int band_rows, const TextureBands<float>& bands,
                     bool half = false);

}  // namespace rockbake
