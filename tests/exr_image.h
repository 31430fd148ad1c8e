// EXR files read back with OpenEXR itself, not with rockbake's EXR code, so a test
// of what rockbake wrote reads it with an independent reader.
#pragma once

#include <OpenEXR/ImfPixelType.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rockbake::test {

// The channels asked for, each a plane of floats (a half widened exactly), row by
// row from the data window's top-left corner: pixel (x, y) at y · width + x.
struct ExrImage {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> planes;
  std::map<std::string, Imf::PixelType> types;  // each channel's type in the file

  const std::vector<float>& plane(const std::string& channel) const { return planes.at(channel); }
  float at(const std::string& channel, int x, int y) const {
    return plane(channel).at(std::size_t(y) * std::size_t(width) + std::size_t(x));
  }
};

// Throws std::runtime_error when the file lacks one of `channels` (and OpenEXR's
// exception when it is not an EXR file).
ExrImage readExr(const std::filesystem::path& file, const std::vector<std::string>& channels = {"R", "G", "B"});

}  // namespace rockbake::test
