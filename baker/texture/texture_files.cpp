#include "texture/texture_files.h"

#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <ImfThreading.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <ostream>
#include <stdexcept>

#include <tbb/task_arena.h>
#include <vector>

#include "platform/atomic_file.h"
#include "texture/png_encoder.h"

namespace rockbake {
namespace {

// OpenEXR compresses a file's blocks on its global thread pool, which has no
// threads until it is given some: without them the ZIP runs on the writing
// thread alone. The pool only grows, up to the bake's own thread count.
void compressOnThreads(int threads) {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (Imf::globalThreadCount() < threads) Imf::setGlobalThreadCount(threads);
}

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

// Serves a map's rows in order from bands of `band_rows` rows made on demand, one band held:
// rows that lie in one band are served in place, others copied together.
template <class T>
class BandRows {
 public:
  BandRows(int size, int channels, int band_rows, const TextureBands<T>& make)
      : size_(size), channels_(channels), band_rows_(std::max(1, band_rows)), make_(make) {}

  const std::uint8_t* rows(int y0, int y1) {
    const std::size_t width = rowWidth();
    const T* first = row(y0);  // makes y0's band when it is not the one held
    if (holds(y1 - 1)) return bytes(first);
    group_.resize(std::size_t(y1 - y0) * width);
    for (int y = y0; y < y1; ++y) std::memcpy(&group_[std::size_t(y - y0) * width], row(y), width * sizeof(T));
    return bytes(group_.data());
  }

 private:
  std::size_t rowWidth() const { return std::size_t(size_) * std::size_t(channels_); }  // samples
  bool holds(int y) const {
    return !band_.pixels.empty() && y >= band_.first_row &&
           std::size_t(y - band_.first_row) * rowWidth() < band_.pixels.size();
  }
  static const std::uint8_t* bytes(const T* p) { return reinterpret_cast<const std::uint8_t*>(p); }

  const T* row(int y) {
    const std::size_t width = rowWidth();
    if (!holds(y)) {
      const int first = y / band_rows_ * band_rows_;
      const int last = std::min(size_, first + band_rows_);
      band_ = TextureImage<T>{};  // the old band is freed before the next is made
      band_ = make_(first, last);
      if (band_.first_row != first || band_.pixels.size() != std::size_t(last - first) * width)
        throw std::runtime_error("the band of rows " + std::to_string(first) + "–" + std::to_string(last) +
                                 " has the wrong size");
    }
    return &band_.pixels[std::size_t(y - band_.first_row) * width];
  }

  int size_, channels_, band_rows_;
  const TextureBands<T>& make_;
  TextureImage<T> band_;
  std::vector<T> group_;
};

template <class T>
void writePngBands(const std::filesystem::path& file, int size, int channels, bool srgb, int band_rows,
                   const TextureBands<T>& bands) {
  if (band_rows >= size) {  // one band: the whole map, encoded in place
    const TextureImage<T> image = bands(0, size);
    if (image.channels != channels) throw std::runtime_error("cannot write PNG " + file.string() + ": wrong channels");
    return writePng(file, image, srgb);
  }
  try {
    BandRows<T> source(size, channels, band_rows, bands);
    texture_detail::writePngFile(file, size, channels, int(8 * sizeof(T)), srgb,
                                 [&](int y0, int y1) { return source.rows(y0, y1); });
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
    case TextureMap::History:
      return name + "_History" + (lod >= 0 ? suffix : "") + ".png";
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

void writeTexturePng(const std::filesystem::path& file, int size, int channels, bool srgb, int band_rows,
                     const TextureBands<std::uint8_t>& bands) {
  if (channels != 3 && channels != 4)
    throw std::runtime_error("cannot write PNG " + file.string() + ": 3 or 4 channels expected");
  writePngBands(file, size, channels, srgb, band_rows, bands);
}

void writeTexturePng(const std::filesystem::path& file, int size, int band_rows,
                     const TextureBands<std::uint16_t>& bands) {
  writePngBands(file, size, 3, false, band_rows, bands);
}

void writeTextureExr(const std::filesystem::path& file, const TextureImage<float>& image, bool half) {
  if (image.channels != 1 || image.size <= 0 ||
      image.pixels.size() != std::size_t(image.size) * std::size_t(image.size))
    throw std::runtime_error("cannot write EXR " + file.string() + ": one channel of size² pixels expected");
  writeTextureExr(
      file, image.size, image.size, [&](int, int) { return image; }, half);
}

void writeTextureExr(const std::filesystem::path& file, int size, int band_rows, const TextureBands<float>& bands,
                     bool half) {
  if (size <= 0) throw std::runtime_error("cannot write EXR " + file.string() + ": no pixels");
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
  const int rows = std::max(1, band_rows);
  try {
    writeFileAtomically(file, [&](std::ostream& out) {
      Imf::Header header(size, size);
      header.channels().insert("Y", Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
      header.compression() = Imf::ZIP_COMPRESSION;
      Stream stream(out, file.string());
      const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
      compressOnThreads(threads);
      Imf::OutputFile exr(stream, header, threads);
      // Each band's slice is addressed as OpenEXR does a region's: its base pointer is where
      // row 0 would be, and OpenEXR reads only the rows written (y from first onwards).
      std::vector<Imath::half> halves;
      for (int first = 0; first < size; first += rows) {
        const int last = std::min(size, first + rows);
        const TextureImage<float> band = bands(first, last);
        if (band.first_row != first || band.pixels.size() != std::size_t(last - first) * std::size_t(size))
          throw std::runtime_error("the band of rows " + std::to_string(first) + "–" + std::to_string(last) +
                                   " has the wrong size");
        Imf::FrameBuffer frame;
        if (half) {
          // Rounded to the nearest half (IEEE 754 binary16), as the file stores it.
          halves.resize(band.pixels.size());
          for (std::size_t i = 0; i < band.pixels.size(); ++i) halves[i] = Imath::half(band.pixels[i]);
          const std::size_t row_bytes = sizeof(Imath::half) * std::size_t(size);
          char* base = reinterpret_cast<char*>(halves.data()) - std::ptrdiff_t(std::size_t(first) * row_bytes);
          frame.insert("Y", Imf::Slice(Imf::HALF, base, sizeof(Imath::half), row_bytes));
        } else {
          const std::size_t row_bytes = sizeof(float) * std::size_t(size);
          char* base = reinterpret_cast<char*>(const_cast<float*>(band.pixels.data())) -
                       std::ptrdiff_t(std::size_t(first) * row_bytes);
          frame.insert("Y", Imf::Slice(Imf::FLOAT, base, sizeof(float), row_bytes));
        }
        exr.setFrameBuffer(frame);
        exr.writePixels(last - first);
      }
    });
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write EXR " + file.string() + ": " + e.what());
  }
}

}  // namespace rockbake
