#include "texture/texture_files.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cstdint>
#include <ostream>
#include <stdexcept>

#include <tbb/task_arena.h>
#include <vector>

#include "core/atomic_file.h"
#include "texture/png_encoder.h"

namespace rockbake {
namespace {

template <class T>
void writePng(const std::filesystem::path& file, const TextureImage<T>& image, bool srgb) {
  const std::size_t row = std::size_t(image.size) * std::size_t(image.channels);
  if (image.size <= 0 || image.pixels.size() != row * std::size_t(image.size))
    throw std::runtime_error("cannot write PNG " + file.string() + ": the image has no pixels or the wrong size");
  try {
    texture_detail::writePngFile(file, image.pixels.data(), image.size, image.channels, int(8 * sizeof(T)), srgb);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write PNG " + file.string() + ": " + e.what());
  }
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
  writePng(file, image, srgb);
}

void writeTexturePng(const std::filesystem::path& file, const TextureImage<std::uint16_t>& image) {
  if (image.channels != 3) throw std::runtime_error("cannot write PNG " + file.string() + ": 3 channels expected");
  writePng(file, image, false);
}

void writeTextureExr(const std::filesystem::path& file, const TextureImage<float>& image) {
  if (image.channels != 1 || image.size <= 0 ||
      image.pixels.size() != std::size_t(image.size) * std::size_t(image.size))
    throw std::runtime_error("cannot write EXR " + file.string() + ": one channel of size² pixels expected");
  // OpenEXR writes straight into the atomic file's stream (it seeks back to patch its offset table).
  class Stream : public Imf::OStream {
   public:
    Stream(std::ostream& out, const std::string& name) : Imf::OStream(name.c_str()), out_(out) {}
    void write(const char c[], int n) override { out_.write(c, n); }
    std::uint64_t tellp() override { return std::uint64_t(out_.tellp()); }
    void seekp(std::uint64_t pos) override { out_.seekp(std::streamoff(pos)); }

   private:
    std::ostream& out_;
  };
  try {
    writeFileAtomically(file, [&](std::ostream& out) {
      Imf::Header header(image.size, image.size);
      header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
      header.compression() = Imf::ZIP_COMPRESSION;
      Stream stream(out, file.string());
      Imf::OutputFile exr(stream, header, std::max(1, tbb::this_task_arena::max_concurrency()));
      Imf::FrameBuffer frame;
      frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(image.pixels.data())),
                                   sizeof(float), sizeof(float) * std::size_t(image.size)));
      exr.setFrameBuffer(frame);
      exr.writePixels(image.size);
    });
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write EXR " + file.string() + ": " + e.what());
  }
}

}  // namespace rockbake
