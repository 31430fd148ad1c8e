#include "core/png_image.h"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

#include "core/atomic_file.h"

namespace rockbake {
namespace {

// A corrupt header can claim any size; refuse before allocating.
constexpr std::uint64_t kMaxPixels = std::uint64_t(1) << 28;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& problem) {
  throw std::runtime_error("cannot read PNG " + file.string() + ": " + problem);
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// png_image_free is safe on a never-started or already-finished image.
struct ImageGuard {
  png_image* image;
  ~ImageGuard() { png_image_free(image); }
};

}  // namespace

namespace {

// Reads any PNG into `format` (PNG_FORMAT_GRAY or PNG_FORMAT_RGB) pixels.
std::vector<std::uint8_t> readPng(const std::filesystem::path& file, png_uint_32 format, int& width, int& height) {
  // Open it ourselves so a missing file reports the OS reason, not libpng's wording.
  std::unique_ptr<std::FILE, FileCloser> stream(std::fopen(file.c_str(), "rb"));
  if (!stream) fail(file, std::generic_category().message(errno));

  // libpng says only "Read Error" for a short non-PNG file; check the signature ourselves.
  png_byte signature[8] = {};
  const std::size_t signature_bytes = std::fread(signature, 1, sizeof signature, stream.get());
  if (signature_bytes != sizeof signature || png_sig_cmp(signature, 0, sizeof signature) != 0) {
    fail(file, "not a PNG file (no PNG signature)");
  }
  std::rewind(stream.get());

  // The simplified API does the setjmp error handling internally and reports
  // failures through image.message, so no longjmp crosses C++ frames here.
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  ImageGuard guard{&image};
  if (!png_image_begin_read_from_stdio(&image, stream.get())) {
    fail(file, std::string("bad PNG header: ") + image.message);
  }
  if (std::uint64_t(image.width) * image.height > kMaxPixels) {
    fail(file, std::to_string(image.width) + "x" + std::to_string(image.height) + " pixels is too large");
  }

  image.format = format;
  width = int(image.width);
  height = int(image.height);
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(image), 0);
  const png_color black{0, 0, 0};
  if (!png_image_finish_read(&image, &black, pixels.data(), 0, nullptr)) {
    fail(file, std::string("truncated or corrupt image data: ") + image.message);
  }
  return pixels;
}

}  // namespace

GrayImage readPngGray(const std::filesystem::path& file) {
  GrayImage result;
  result.pixels = readPng(file, PNG_FORMAT_GRAY, result.width, result.height);
  return result;
}

RgbImage readPngRgb(const std::filesystem::path& file) {
  RgbImage result;
  result.pixels = readPng(file, PNG_FORMAT_RGB, result.width, result.height);
  return result;
}

void writePngRgb(const std::filesystem::path& file, const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
    throw std::runtime_error("cannot write PNG " + file.string() + ": the image has no pixels or the wrong size");
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = PNG_FORMAT_RGB;
  ImageGuard guard{&png};
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.pixels.data(), 0, nullptr))
    throw std::runtime_error("cannot write PNG " + file.string() + ": " + png.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), 0, nullptr))
    throw std::runtime_error("cannot write PNG " + file.string() + ": " + png.message);
  bytes.resize(size);
  writeFileAtomically(file, bytes);
}

}  // namespace rockbake
