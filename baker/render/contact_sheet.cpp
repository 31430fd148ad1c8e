#include "render/contact_sheet.h"

#include <algorithm>
#include <cmath>

#include "render/font_text.h"

namespace rockbake {
namespace {

constexpr std::array<std::uint8_t, 3> kBackground{32, 32, 32};
constexpr std::array<std::uint8_t, 3> kPlaceholder{96, 96, 96};
constexpr std::array<std::uint8_t, 3> kLabel{230, 230, 230};
constexpr int kFontPixels = 13;

void fill(RgbImage& image, int x0, int y0, int w, int h, std::array<std::uint8_t, 3> color) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x)
      std::copy(color.begin(), color.end(), &image.pixels[(std::size_t(y) * std::size_t(image.width) + x) * 3]);
}

void blit(RgbImage& target, const RgbImage& source, int x0, int y0) {
  for (int y = 0; y < source.height; ++y)
    std::copy_n(&source.pixels[std::size_t(y) * std::size_t(source.width) * 3], std::size_t(source.width) * 3,
                &target.pixels[(std::size_t(y0 + y) * std::size_t(target.width) + std::size_t(x0)) * 3]);
}

void centredText(TextRasterizer& font, RgbImage& image, int x0, int width, int top, int height,
                 const std::string& text) {
  const std::string shown = font.fit(text, width - 4);
  const int x = x0 + (width - font.width(shown)) / 2;
  const int baseline = top + (height + font.ascender()) / 2 - 2;
  font.draw(image, x, baseline, shown, kLabel);
}

}  // namespace

RgbImage fitImage(const RgbImage& image, int max_width, int max_height) {
  const double scale = std::min({1.0, double(max_width) / image.width, double(max_height) / image.height});
  RgbImage out;
  out.width = std::max(1, int(std::lround(image.width * scale)));
  out.height = std::max(1, int(std::lround(image.height * scale)));
  out.pixels.resize(std::size_t(out.width) * std::size_t(out.height) * 3);
  // Each output pixel averages the source pixels whose centres fall in its footprint.
  for (int y = 0; y < out.height; ++y) {
    const int y0 = y * image.height / out.height, y1 = std::max(y0 + 1, (y + 1) * image.height / out.height);
    for (int x = 0; x < out.width; ++x) {
      const int x0 = x * image.width / out.width, x1 = std::max(x0 + 1, (x + 1) * image.width / out.width);
      for (int k = 0; k < 3; ++k) {
        unsigned long sum = 0;
        for (int sy = y0; sy < y1; ++sy)
          for (int sx = x0; sx < x1; ++sx)
            sum += image.pixels[(std::size_t(sy) * std::size_t(image.width) + std::size_t(sx)) * 3 + k];
        const auto count = static_cast<unsigned long>((y1 - y0) * (x1 - x0));
        out.pixels[(std::size_t(y) * std::size_t(out.width) + std::size_t(x)) * 3 + k] =
            std::uint8_t((sum + count / 2) / count);
      }
    }
  }
  return out;
}

RgbImage makeContactSheet(const std::vector<ContactSheetItem>& items) {
  const int n = int(items.size());
  const int columns = std::max(1, std::min(n, kColumns));
  const int rows = std::max(1, (n + columns - 1) / columns);
  RgbImage sheet;
  sheet.width = columns * kThumbWidth + (columns + 1) * kGap;
  sheet.height = rows * (kThumbHeight + kLabelHeight) + (rows + 1) * kGap;
  sheet.pixels.resize(std::size_t(sheet.width) * std::size_t(sheet.height) * 3);
  fill(sheet, 0, 0, sheet.width, sheet.height, kBackground);
  TextRasterizer font(defaultFontFile(), kFontPixels);

  for (int i = 0; i < n; ++i) {
    const ContactSheetItem& item = items[std::size_t(i)];
    const int x0 = kGap + (i % columns) * (kThumbWidth + kGap);
    const int y0 = kGap + (i / columns) * (kThumbHeight + kLabelHeight + kGap);
    std::string placeholder = item.placeholder.empty() ? "no render" : item.placeholder;
    bool drawn = false;
    if (!item.render.empty()) {
      try {
        const RgbImage thumb = fitImage(readPngRgb(item.render), kThumbWidth, kThumbHeight);
        blit(sheet, thumb, x0 + (kThumbWidth - thumb.width) / 2, y0 + (kThumbHeight - thumb.height) / 2);
        drawn = true;
      } catch (const std::runtime_error&) {
        placeholder = "unreadable render";
      }
    }
    if (!drawn) {
      fill(sheet, x0, y0, kThumbWidth, kThumbHeight, kPlaceholder);
      centredText(font, sheet, x0, kThumbWidth, y0 + kThumbHeight / 2 - 24, 20, placeholder);
      centredText(font, sheet, x0, kThumbWidth, y0 + kThumbHeight / 2 + 4, 20, item.name);
    }
    centredText(font, sheet, x0, kThumbWidth, y0 + kThumbHeight, kLabelHeight, item.name);
  }
  return sheet;
}

}  // namespace rockbake
