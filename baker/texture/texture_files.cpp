#include "texture/texture_files.h"

#include <png.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>

#include <csetjmp>
#include <stdexcept>
#include <vector>

#include "core/atomic_file.h"

namespace rockbake {
namespace {

void appendBytes(png_structp png, png_bytep data, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}
void flushNothing(png_structp) {}

// libpng reports errors by longjmp: nothing here has a destructor to skip. Returns false on failure.
bool encodePng(std::string* out, int size, int depth, int colour_type, bool srgb, png_bytepp rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, out, appendBytes, flushNothing);
  png_set_IHDR(png, info, png_uint_32(size), png_uint_32(size), depth, colour_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (srgb) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_set_compression_level(png, 1);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_write_info(png, info);
  if (depth == 16) png_set_swap(png);  // PNG stores 16-bit samples big-endian
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

template <class T>
void writePng(const std::filesystem::path& file, const TextureImage<T>& image, int colour_type, bool srgb) {
  const std::size_t row = std::size_t(image.size) * std::size_t(image.channels);
  if (image.size <= 0 || image.pixels.size() != row * std::size_t(image.size))
    throw std::runtime_error("cannot write PNG " + file.string() + ": the image has no pixels or the wrong size");
  std::vector<png_bytep> rows(std::size_t(image.size));
  for (std::size_t y = 0; y < rows.size(); ++y)
    rows[y] = reinterpret_cast<png_bytep>(const_cast<T*>(image.pixels.data() + y * row));
  std::string bytes;
  if (!encodePng(&bytes, image.size, int(8 * sizeof(T)), colour_type, srgb, rows.data()))
    throw std::runtime_error("cannot write PNG " + file.string() + ": libpng failed to encode it");
  writeFileAtomically(file, bytes);
}

}  // namespace

std::string textureFileName(const std::string& name, TextureMap map, int lod) {
  const std::string suffix = "_LOD" + std::to_string(lod < 0 ? 0 : lod);
  switch (map) {
    case TextureMap::BaseColor:
      return name + "_BaseColor" + (lod >= 0 ? suffix : "") + ".png";
    case TextureMap::Normal:
      return name + "_Normal" + suffix + ".png";
    case TextureMap::Orm:
      return name + "_ORM" + (lod >= 0 ? suffix : "") + ".png";
    case TextureMap::Height:
      return name + "_Height" + (lod >= 0 ? suffix : "") + ".exr";
    case TextureMap::Mask:
      return name + "_Mask" + (lod >= 0 ? suffix : "") + ".png";
  }
  return name;
}

void writeTexturePng(const std::filesystem::path& file, const TextureImage<std::uint8_t>& image, bool srgb) {
  if (image.channels != 3 && image.channels != 4)
    throw std::runtime_error("cannot write PNG " + file.string() + ": 3 or 4 channels expected");
  writePng(file, image, image.channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, srgb);
}

void writeTexturePng(const std::filesystem::path& file, const TextureImage<std::uint16_t>& image) {
  if (image.channels != 3) throw std::runtime_error("cannot write PNG " + file.string() + ": 3 channels expected");
  writePng(file, image, PNG_COLOR_TYPE_RGB, false);
}

void writeTextureExr(const std::filesystem::path& file, const TextureImage<float>& image) {
  if (image.channels != 1 || image.size <= 0 ||
      image.pixels.size() != std::size_t(image.size) * std::size_t(image.size))
    throw std::runtime_error("cannot write EXR " + file.string() + ": one channel of size² pixels expected");
  std::string bytes;
  try {
    Imf::Header header(image.size, image.size);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::StdOSStream os;
    {
      Imf::OutputFile out(os, header, 1);
      Imf::FrameBuffer frame;
      frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(image.pixels.data())),
                                   sizeof(float), sizeof(float) * std::size_t(image.size)));
      out.setFrameBuffer(frame);
      out.writePixels(image.size);
    }
    bytes = os.str();
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write EXR " + file.string() + ": " + e.what());
  }
  writeFileAtomically(file, bytes);
}

}  // namespace rockbake
