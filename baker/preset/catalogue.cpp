#include "preset/catalogue.h"

#include <algorithm>

#include "platform/data_dir.h"

namespace rockbake {

namespace fs = std::filesystem;

fs::path catalogueDir() {
  const fs::path data = dataDir();
  return data.empty() ? fs::path() : data / "presets";
}

std::optional<std::string> catalogueName(const std::string& written) {
  if (written.rfind(kCataloguePrefix, 0) != 0) return std::nullopt;
  return written.substr(kCataloguePrefix.size());
}

std::optional<std::string> catalogueNameProblem(const std::string& name) {
  if (name.empty()) return "names no catalogue preset (nothing after 'rockbake:')";
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '\\')
      return "'" + name + "' is not a catalogue name (a control byte or a backslash)";
  const fs::path path(name);
  if (path.is_absolute()) return "'" + name + "' is not a catalogue name: it is an absolute path";
  for (const auto& part : path)
    if (part == ".." || part == ".")
      return "'" + name + "' is not a catalogue name: it may not hold '.' or '..'";
  return std::nullopt;
}

std::vector<std::string> cataloguePresetNames() {
  std::vector<std::string> names;
  std::error_code ec;
  const fs::path dir = catalogueDir();
  if (dir.empty()) return names;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".yaml" && entry.is_regular_file(ec)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace rockbake
