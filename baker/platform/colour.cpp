#include "platform/colour.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "platform/data_dir.h"

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
}  // namespace

std::filesystem::path defaultOcioConfig() {
  return requireDataPath("render_templates/ocio/config.ocio");
}

std::array<float, 3> srgbToSceneLinear(const std::array<float, 3>& srgb, const std::filesystem::path& cfg) {
  return apply(processorsFor(cfg).to_linear, srgb);
}

std::array<float, 3> sceneLinearToDisplay(const std::array<float, 3>& linear, const std::filesystem::path& cfg) {
  return apply(processorsFor(cfg).to_display, linear);
}

void sceneLinearToDisplay(std::vector<float>& rgb, int width, int height, const std::filesystem::path& cfg) {
  if (rgb.size() != std::size_t(width) * std::size_t(height) * 3)
    throw std::invalid_argument("sceneLinearToDisplay: the buffer does not hold width × height RGB pixels");
  OCIO::PackedImageDesc desc(rgb.data(), width, height, 3);
  processorsFor(cfg).to_display->apply(desc);
}

float linearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t linearToSrgbByte(float linear) {
  // steps[b]: the least float in [0, 1] whose code is above b, found by bisection over the
  // floats' bit patterns (in order for non-negative floats). The codes rise with the value, so
  // the code of x is the number of steps at or below it.
  static const std::array<float, 255> steps = [] {
    const auto code = [](float x) { return long(std::lround(linearToSrgb(x) * 255.0f)); };
    std::array<float, 255> s{};
    for (long b = 0; b < 255; ++b) {
      std::uint32_t lo = 0, hi = std::bit_cast<std::uint32_t>(1.0f);  // code(lo) <= b < code(hi)
      while (hi - lo > 1) {
        const std::uint32_t mid = lo + (hi - lo) / 2;
        (code(std::bit_cast<float>(mid)) > b ? hi : lo) = mid;
      }
      s[std::size_t(b)] = std::bit_cast<float>(hi);
    }
    return s;
  }();
  if (!(linear > 0.0f)) return 0;  // NaN too
  // A binary search of fixed steps, without branches on the value (they would not be predicted).
  std::size_t code = 0;
  for (std::size_t half = 128; half > 0; half /= 2) code += steps[code + half - 1] <= linear ? half : 0;
  return std::uint8_t(code);
}

float srgbToLinear(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace rockbake
