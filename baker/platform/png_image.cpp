#include "platform/png_image.h"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

#include "platform/atomic_file.h"

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
  png_byte head[33] = {};  // the signature and the IHDR chunk
  const std::size_t head_bytes = std::fread(head, 1, sizeof head, stream.get());
  if (head_bytes < 8 || png_sig_cmp(head, 0, 8) != 0) {
    fail(file, "not a PNG file (no PNG signature)");
  }
  if (head_bytes == sizeof head && std::memcmp(head + 12, "IHDR", 4) == 0) {
    // Deflate packs at most 1032 bytes into one: a header claiming more pixel data than the file can
    // hold is refused before anything is allocated for the pixels.
    const auto be32 = [&](int at) {
      return std::uint64_t(head[at]) << 24 | std::uint64_t(head[at + 1]) << 16 | std::uint64_t(head[at + 2]) << 8 |
             std::uint64_t(head[at + 3]);
    };
    const std::uint64_t w = be32(16), h = be32(20), depth = head[24];
    const int colour_type = head[25];
    const std::uint64_t channels = colour_type == 2 ? 3 : colour_type == 4 ? 2 : colour_type == 6 ? 4 : 1;
    const std::uint64_t raw = h * ((w * channels * depth + 7) / 8 + 1);
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(file, ec);
    if (w * h > kMaxPixels)
      fail(file, std::to_string(w) + "x" + std::to_string(h) + " pixels is too large (at most " +
                     std::to_string(kMaxPixels >> 20) + " M pixels)");
    if (!ec && raw > size * 1032 + 65536)
      fail(file, "truncated: a " + std::to_string(w) + "x" + std::to_string(h) + " image needs more data than " +
                     std::to_string(size) + " bytes can hold");
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

std::string encodePngRgb(const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
    throw std::runtime_error("the image has no pixels or the wrong size");
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = PNG_FORMAT_RGB;
  ImageGuard guard{&png};
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.pixels.data(), 0, nullptr))
    throw std::runtime_error(png.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), 0, nullptr))
    throw std::runtime_error(png.message);
  bytes.resize(size);
  return bytes;
}

void writePngRgb(const std::filesystem::path& file, const RgbImage& image) {
  std::string bytes;
  try {
    bytes = encodePngRgb(image);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot write PNG " + file.string() + ": " + e.what());
  }
  writeFileAtomically(file, bytes);
}

}  // namespace rockbake
