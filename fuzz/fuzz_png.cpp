// The PNG reader (image shapes, contact sheets): any bytes as a .png file.
// Refusals are std::runtime_error; nothing may be allocated for pixels a
// file this size cannot hold (libFuzzer's -malloc_limit_mb catches that).
#include <cstdint>
#include <stdexcept>

#include "platform/png_image.h"
#include "fuzz_support.h"

using namespace rockbake;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = fuzz::scratchDir("png") / "image.png";
  fuzz::writeFile(file, {reinterpret_cast<const char*>(data), size});
  GrayImage gray;
  if (fuzz::refusesOnlyWith<std::runtime_error>([&] { gray = readPngGray(file); })) {
    if (gray.pixels.size() != std::size_t(gray.width) * std::size_t(gray.height))
      fuzz::finding("the grey image's pixels do not match its size");
    RgbImage rgb;
    if (!fuzz::refusesOnlyWith<std::runtime_error>([&] { rgb = readPngRgb(file); }))
      fuzz::finding("a PNG read as grey fails as RGB");
    if (rgb.width != gray.width || rgb.height != gray.height) fuzz::finding("grey and RGB sizes differ");
  }
  return 0;
}
