#include "render/preview.h"

#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "platform/png_image.h"
#include "preset/render_templates.h"

namespace rockbake {

std::filesystem::path defaultRenderTemplatesDir() {
  return renderTemplatesDir();
}

RgbImage exrToDisplay(const std::filesystem::path& exr, const std::filesystem::path& cfg) {
  int width = 0, height = 0;
  std::vector<float> rgb;
  try {
    Imf::RgbaInputFile in(exr.string().c_str());
    const Imath::Box2i dw = in.dataWindow();
    width = dw.max.x - dw.min.x + 1;
    height = dw.max.y - dw.min.y + 1;
    Imf::Array2D<Imf::Rgba> px(height, width);
    in.setFrameBuffer(&px[0][0] - dw.min.x - std::ptrdiff_t(dw.min.y) * width, 1, std::size_t(width));
    in.readPixels(dw.min.y, dw.max.y);
    rgb.resize(std::size_t(width) * std::size_t(height) * 3);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        float* o = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
        o[0] = px[y][x].r, o[1] = px[y][x].g, o[2] = px[y][x].b;
      }
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read " + exr.string() + ": " + e.what());
  }
  sceneLinearToDisplay(rgb, width, height, cfg);
  RgbImage image;
  image.width = width;
  image.height = height;
  image.pixels.resize(rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
    image.pixels[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
  }
  return image;
}

void exrToPng(const std::filesystem::path& exr, const std::filesystem::path& png_path,
              const std::filesystem::path& cfg) {
  writePngRgb(png_path, exrToDisplay(exr, cfg));
}

}  // namespace rockbake
