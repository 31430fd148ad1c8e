#include "render/color.h"

#include <png.h>

#include <OpenColorIO/OpenColorIO.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "preset/render_templates.h"

#ifndef ROCKBAKE_RENDER_TEMPLATES_DIR
#define ROCKBAKE_RENDER_TEMPLATES_DIR "render_templates"
#endif

namespace OCIO = OCIO_NAMESPACE;

namespace rockbake {
namespace {

struct Processors {
  OCIO::ConstCPUProcessorRcPtr to_linear;   // sRGB - Texture -> scene_linear
  OCIO::ConstCPUProcessorRcPtr to_display;  // scene_linear -> default display / view
};

const Processors& processorsFor(const std::filesystem::path& config_path) {
  static std::mutex mutex;
  static std::map<std::string, Processors> cache;
  const std::string key = config_path.string();
  std::lock_guard<std::mutex> lock(mutex);
  const auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  try {
    OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(key.c_str());
    config->validate();
    Processors p;
    p.to_linear = config->getProcessor("sRGB - Texture", OCIO::ROLE_SCENE_LINEAR)->getDefaultCPUProcessor();
    const char* display = config->getDefaultDisplay();
    auto dv = OCIO::DisplayViewTransform::Create();
    dv->setSrc(OCIO::ROLE_SCENE_LINEAR);
    dv->setDisplay(display);
    dv->setView(config->getDefaultView(display));
    p.to_display = config->getProcessor(dv)->getDefaultCPUProcessor();
    return cache.emplace(key, std::move(p)).first->second;
  } catch (const OCIO::Exception& e) {
    throw std::runtime_error("OpenColorIO config " + key + ": " + e.what());
  }
}

std::array<float, 3> apply(const OCIO::ConstCPUProcessorRcPtr& p, const std::array<float, 3>& in) {
  float px[3] = {in[0], in[1], in[2]};
  p->applyRGB(px);
  return {px[0], px[1], px[2]};
}

std::string encodePng(int width, int height, const std::vector<unsigned char>& rgb, const std::string& label) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) throw std::runtime_error("cannot encode " + label + ": libpng out of memory");
  png_infop info = png_create_info_struct(png);
  std::string bytes;
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("cannot encode " + label + ": libpng error");
  }
  png_set_write_fn(
      png, &bytes,
      [](png_structp p, png_bytep data, png_size_t n) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<const char*>(data), n);
      },
      nullptr);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y)
    png_write_row(png, const_cast<png_bytep>(rgb.data() + std::size_t(y) * std::size_t(width) * 3));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

}  // namespace

std::filesystem::path defaultRenderTemplatesDir() {
  return renderTemplatesDir();
}
// The shipped config, also when the templates come from a folder of the user's own.
std::filesystem::path defaultOcioConfig() {
  return std::filesystem::path(ROCKBAKE_RENDER_TEMPLATES_DIR) / "ocio" / "config.ocio";
}

std::array<float, 3> srgbToSceneLinear(const std::array<float, 3>& srgb, const std::filesystem::path& cfg) {
  return apply(processorsFor(cfg).to_linear, srgb);
}

std::array<float, 3> sceneLinearToDisplay(const std::array<float, 3>& linear, const std::filesystem::path& cfg) {
  return apply(processorsFor(cfg).to_display, linear);
}

void exrToPng(const std::filesystem::path& exr, const std::filesystem::path& png_path,
              const std::filesystem::path& cfg) {
  const Processors& p = processorsFor(cfg);
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
  OCIO::PackedImageDesc desc(rgb.data(), width, height, 3);
  p.to_display->apply(desc);
  std::vector<unsigned char> bytes(rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
    bytes[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
  }
  writeFileAtomically(png_path, encodePng(width, height, bytes, png_path.string()));
}

}  // namespace rockbake
