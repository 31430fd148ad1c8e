// A library's contact sheet (docs/libraries.md): one thumbnail per asset with its name
// printed under it, as an 8-bit sRGB PNG.
//
// Layout, all in pixels: tiles of kThumbWidth × kThumbHeight with a
// kLabelHeight label strip below each, kGap between tiles and around the
// edge, min(N, kColumns) columns:
//   width  = columns · kThumbWidth + (columns + 1) · kGap
//   height = rows · (kThumbHeight + kLabelHeight) + (rows + 1) · kGap
// A thumbnail is the asset's render scaled (box filter) to fit its tile,
// centred; an asset without a render gets a grey placeholder tile naming why.
// The same items give the same bytes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "platform/png_image.h"

namespace rockbake {

struct ContactSheetItem {
  std::string name;              // printed under the tile
  std::filesystem::path render;  // a PNG; empty: placeholder tile
  std::string placeholder;       // the placeholder's text ("failed", "no render")
};

inline constexpr int kThumbWidth = 192;
inline constexpr int kThumbHeight = 144;
inline constexpr int kLabelHeight = 22;
inline constexpr int kGap = 8;
inline constexpr int kColumns = 6;

// Throws std::runtime_error when the font is missing; an unreadable render
// becomes a placeholder ("unreadable render").
RgbImage makeContactSheet(const std::vector<ContactSheetItem>& items);

// Scales `image` to fit in max_width × max_height keeping its aspect ratio
// (area average); never enlarges.
RgbImage fitImage(const RgbImage& image, int max_width, int max_height);

}  // namespace rockbake
