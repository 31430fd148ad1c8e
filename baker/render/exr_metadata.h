// EXR headers that say where a render came from (docs/rendering.md), and the turntable
// contact sheet. Pixels stay half-float RGB(A).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace rockbake {

struct RenderMetadata {
  std::string preset;       // rockbake:preset
  std::string seed;         // rockbake:seed (decimal: a 64-bit seed does not fit a float)
  std::string preset_hash;  // rockbake:preset_hash
  std::string version;      // rockbake:version
  int frame = 0;            // rockbake:frame (float attribute); -1 for a contact sheet
  // World coordinates, z up. rockbake:camera is the string
  // "location x y z look_at x y z angle a"; rockbake:camera_angle a float.
  std::array<double, 3> camera_location{};
  std::array<double, 3> camera_look_at{};
  double camera_angle = 0;
};

// Re-writes `source` (an EXR) as `target` (may be the same path; written
// atomically) with the attributes above added to its header and the time
// stamp ("creation") removed.
void writeExrWithMetadata(const std::filesystem::path& source, const std::filesystem::path& target,
                          const RenderMetadata& metadata);

// One band of an image rendered in parts: `file` (the whole image's size) holds rows
// [first_row, end_row); its other rows are ignored.
struct ExrBand {
  std::filesystem::path file;
  int first_row = 0;
  int end_row = 0;
};

// Joins `bands` (one size, their rows covering the image once) into `target` as
// writeExrWithMetadata writes one file: the header is the first band's. The same pixels
// give the same bytes however the rows were split.
void joinExrBands(const std::vector<ExrBand>& bands, const std::filesystem::path& target,
                  const RenderMetadata& metadata);

// Lays `frames` (EXRs of equal size) out left to right, top to bottom in a grid
// of `columns` columns (0: ceil(sqrt(n))) and writes a half RGBA EXR atomically.
// Returns {width, height} of the sheet.
std::array<int, 2> writeContactSheet(const std::vector<std::filesystem::path>& frames,
                                     const std::filesystem::path& target, const RenderMetadata& metadata,
                                     int columns = 0);

}  // namespace rockbake
