// A PNG encoder for large maps (docs/textures.md): PNG's container (ISO/IEC 15948: signature,
// IHDR, an sRGB chunk with its gAMA fallback where asked, IDAT, IEND, each with its CRC)
// around one zlib stream compressed in parallel, as pigz does it: the filtered rows (Up
// filter) are cut into bands of kBandRows rows, each band deflated on its own (zlib level 4)
// and ended with a sync flush, the last one finished, and the bands' Adler-32 checksums
// combined. libpng compresses on one thread only, and a 16-bit 2048² normal map takes it
// most of a second. Sixteen bands at a time are deflated and written as one IDAT chunk (the
// zlib stream runs on across chunks), into the file atomically (platform/atomic_file.h), so only
// their output is held at once. The bytes depend only on the pixels
// (the bands are fixed, not the thread count). Any PNG reader reads the result.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>

namespace rockbake::texture_detail {

// `pixels`: size × size texels of `channels` (1..4) samples, row-major, 8 or 16 `bits` each
// (16-bit samples in the host's order). Throws std::runtime_error if zlib or the write fails.
void writePngFile(const std::filesystem::path& file, const void* pixels, int size, int channels, int bits, bool srgb);

// Rows y0 … y1 − 1 of the image, contiguous (y1 − y0 rows of size · channels samples); they
// need only stay valid until the next call.
using PngRows = std::function<const std::uint8_t*(int y0, int y1)>;

// The same file from rows pulled in order, kGroup · kBandRows (512) at a time: a map made in
// bands is encoded without ever being whole in memory. Exceptions from `rows` propagate.
void writePngFile(const std::filesystem::path& file, int size, int channels, int bits, bool srgb, const PngRows& rows);

}  // namespace rockbake::texture_detail
