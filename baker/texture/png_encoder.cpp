#include "texture/png_encoder.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "platform/atomic_file.h"

namespace rockbake::texture_detail {
namespace {

constexpr int kBandRows = 32;
constexpr int kGroup = 16;  // bands a chunk
// zlib level 6, filtered-data strategy: on a house set's maps 3.5 % smaller than level 4 for
// about twice its time, which the colour maps at a quarter of their texels (texture_params.h)
// more than pay for; level 9 saves 3 % more for five to ten times as long (bench/README.md).
constexpr int kLevel = 6;

void put32(std::string& out, std::uint32_t v) {
  const char b[4] = {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  out.append(b, 4);
}

void chunk(std::string& out, const char type[4], const std::string& data) {
  put32(out, std::uint32_t(data.size()));
  const std::size_t start = out.size();
  out.append(type, 4);
  out += data;
  const auto crc = crc32(0, reinterpret_cast<const Bytef*>(out.data() + start), uInt(out.size() - start));
  put32(out, std::uint32_t(crc));
}

// One band of rows, filtered (Up: each byte minus the byte above it, PNG's filter type 2) and
// deflated raw; `last` finishes the stream, else a sync flush ends it on a byte boundary.
// `rows`: the band's rows, `above`: the row before them (nullptr for the image's first).
std::string deflateBand(const std::uint8_t* rows, const std::uint8_t* above_row, std::size_t stride, int bits,
                        int count, bool last, std::uint32_t& adler) {
  std::vector<std::uint8_t> filtered(std::size_t(count) * (stride + 1));
  std::vector<std::uint8_t> above(stride, 0), row(stride);
  const auto load = [&](const std::uint8_t* src, std::vector<std::uint8_t>& into) {
    if (bits == 16) {  // big-endian samples
      for (std::size_t i = 0; i < stride; i += 2) into[i] = src[i + 1], into[i + 1] = src[i];
    } else {
      std::memcpy(into.data(), src, stride);
    }
  };
  if (above_row) load(above_row, above);
  for (int y = 0; y < count; ++y) {
    load(rows + std::size_t(y) * stride, row);
    std::uint8_t* out = &filtered[std::size_t(y) * (stride + 1)];
    out[0] = 2;  // Up
    for (std::size_t i = 0; i < stride; ++i) out[i + 1] = std::uint8_t(row[i] - above[i]);
    std::swap(row, above);
  }
  adler = std::uint32_t(adler32(1, filtered.data(), uInt(filtered.size())));
  z_stream z{};
  if (deflateInit2(&z, kLevel, Z_DEFLATED, -15, 8, Z_FILTERED) != Z_OK)
    throw std::runtime_error("zlib: deflateInit2 failed");
  std::string out(deflateBound(&z, uLong(filtered.size())) + 16, '\0');
  z.next_in = filtered.data();
  z.avail_in = uInt(filtered.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = uInt(out.size());
  const int status = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
  const bool ok = last ? status == Z_STREAM_END : status == Z_OK && z.avail_in == 0;
  out.resize(out.size() - z.avail_out);
  out.shrink_to_fit();  // it was sized for the worst case, and sixteen are held until their chunk is written
  deflateEnd(&z);
  if (!ok) throw std::runtime_error("zlib: deflate failed");
  return out;
}

// Encodes with `rowsAt` (png_encoder.h's PngRows) called for consecutive groups in order.
void encodePng(const std::filesystem::path& file, int size, int channels, int bits, bool srgb, const PngRows& rowsAt) {
  if (size <= 0 || channels < 1 || channels > 4 || (bits != 8 && bits != 16))
    throw std::runtime_error("encodePng: unsupported image");
  const std::size_t stride = std::size_t(size) * std::size_t(channels) * std::size_t(bits / 8);
  const int bands = (size + kBandRows - 1) / kBandRows;
  std::string head("\x89PNG\r\n\x1a\n", 8);
  std::string header;
  put32(header, std::uint32_t(size));
  put32(header, std::uint32_t(size));
  static constexpr char kColourType[5] = {0, 0, 4, 2, 6};  // grey, grey + alpha, RGB, RGBA
  header += char(bits);
  header += kColourType[channels];
  header.append(3, '\0');  // deflate, adaptive filtering, no interlace
  chunk(head, "IHDR", header);
  if (srgb) {
    chunk(head, "sRGB", std::string(1, '\0'));  // perceptual rendering intent
    std::string gamma;
    put32(gamma, 45455);  // 1 / 2.2, for readers that know no sRGB chunk
    chunk(head, "gAMA", gamma);
  }
  writeFileAtomically(file, [&](std::ostream& out) {
    out << head;
    // kGroup bands at a time, deflated in parallel and written as one IDAT chunk (the zlib
    // stream runs on across chunks), so only their rows and output are held at once.
    std::uint32_t checksum = 1;
    std::vector<std::uint8_t> previous;  // the last row of the group before (the Up filter's row above)
    for (int first = 0; first < bands; first += kGroup) {
      const int last = std::min(bands, first + kGroup);
      const int y0 = first * kBandRows, y1 = std::min(size, last * kBandRows);
      const std::uint8_t* group = rowsAt(y0, y1);
      std::vector<std::string> deflated(static_cast<std::size_t>(last - first));
      std::vector<std::uint32_t> adler(deflated.size());
      tbb::parallel_for(first, last, [&](int b) {
        const int row0 = b * kBandRows, row1 = std::min(size, (b + 1) * kBandRows);
        const std::uint8_t* rows = group + std::size_t(row0 - y0) * stride;
        const std::uint8_t* above = b == first ? (first == 0 ? nullptr : previous.data()) : rows - stride;
        deflated[std::size_t(b - first)] =
            deflateBand(rows, above, stride, bits, row1 - row0, b == bands - 1, adler[std::size_t(b - first)]);
      });
      previous.assign(group + std::size_t(y1 - 1 - y0) * stride, group + std::size_t(y1 - y0) * stride);
      std::string data = first == 0 ? std::string("\x78\x5e", 2) : std::string();  // zlib: deflate, fast
      for (int b = first; b < last; ++b) {
        data += deflated[std::size_t(b - first)];
        const int rows = std::min(size, (b + 1) * kBandRows) - b * kBandRows;
        checksum = std::uint32_t(
            adler32_combine(checksum, adler[std::size_t(b - first)], z_off_t(std::size_t(rows) * (stride + 1))));
      }
      if (last == bands) put32(data, checksum);
      std::string idat;
      chunk(idat, "IDAT", data);
      out << idat;
    }
    std::string tail;
    chunk(tail, "IEND", std::string());
    out << tail;
  });
}

}  // namespace

void writePngFile(const std::filesystem::path& file, const void* pixels, int size, int channels, int bits, bool srgb) {
  const auto* image = static_cast<const std::uint8_t*>(pixels);
  const std::size_t stride = std::size_t(std::max(size, 0)) * std::size_t(channels) * std::size_t(bits / 8);
  encodePng(file, size, channels, bits, srgb, [&](int y0, int) { return image + std::size_t(y0) * stride; });
}

void writePngFile(const std::filesystem::path& file, int size, int channels, int bits, bool srgb, const PngRows& rows) {
  encodePng(file, size, channels, bits, srgb, rows);
}

}  // namespace rockbake::texture_detail
