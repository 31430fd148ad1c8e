// Reading PNGs for image-based initial shapes (SPEC §2.8: white is rock).
#pragma once

#include <cstdint>
#include <filesystem>
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

}  // namespace rockbake
