#include "preset/preset.h"

namespace rockbake {

SourceLocation Preset::locate(const std::string& key_path) const {
  for (std::string path = key_path;;) {
    if (const auto it = locations.find(path); it != locations.end()) return it->second;
    const std::size_t dot = path.rfind('.');
    if (dot == std::string::npos) break;
    path.resize(dot);
  }
  return {file.string(), 0, 0};
}

}  // namespace rockbake
