// PNG images: reading for image-based initial shapes (docs/model.md §8: white is
// rock); reading and writing 8-bit RGB for previews and contact sheets.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rockbake {

// 8-bit luminance, row-major, row 0 = top of the image.
struct GrayImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // width * height

  std::uint8_t at(int x, int y) const { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

// Any PNG (grey, RGB, palette, 1..16 bits, with or without alpha) becomes 8-bit
// sRGB luminance; alpha is composited over black, so transparent reads as air.
// Throws std::runtime_error naming the file and the problem (missing, not a
// PNG, truncated or corrupt, too large).
GrayImage readPngGray(const std::filesystem::path& file);

// 8-bit RGB, row-major, row 0 = top; pixels[3 * (y * width + x) + channel].
struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3
};

// Any PNG as 8-bit RGB (alpha composited over black). Errors as readPngGray.
RgbImage readPngRgb(const std::filesystem::path& file);

// `image` as the bytes of an 8-bit RGB PNG (no time stamp or other varying chunk). Throws
// std::runtime_error when it has no pixels or the wrong size.
std::string encodePngRgb(const RgbImage& image);

// Writes `image` as an 8-bit RGB PNG, atomically (platform/atomic_file.h). The bytes
// depend only on the pixels: no time stamp or other varying chunk.
void writePngRgb(const std::filesystem::path& file, const RgbImage& image);

}  // namespace rockbake
