// Drawing text into 8-bit RGB images with FreeType (labels on contact sheets).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "platform/png_image.h"

namespace rockbake {

// DejaVu Sans, from Debian's fonts-dejavu-core.
std::filesystem::path defaultFontFile();

// One font face at one pixel size. Glyphs are FreeType's hinted 8-bit
// coverage, so the same text gives the same pixels on every run. Not
// thread-safe: use one per thread.
class TextRasterizer {
 public:
  // Throws std::runtime_error naming the font file (and the package for the
  // default font) when it cannot be loaded.
  TextRasterizer(const std::filesystem::path& font_file, int pixel_height);
  ~TextRasterizer();
  TextRasterizer(const TextRasterizer&) = delete;
  TextRasterizer& operator=(const TextRasterizer&) = delete;

  // Advance width of `text` in pixels (bytes are taken as Latin-1 code points).
  int width(const std::string& text);
  // Distance from the baseline up to the top of the tallest glyphs.
  int ascender() const;
  // Blends `text` in `color` with its left end at x and its baseline at
  // baseline_y; pixels outside the image are skipped.
  void draw(RgbImage& image, int x, int baseline_y, const std::string& text, std::array<std::uint8_t, 3> color);
  // `text` shortened with "..." to fit max_width pixels.
  std::string fit(const std::string& text, int max_width);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbake
