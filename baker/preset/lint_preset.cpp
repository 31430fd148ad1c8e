// `rockbake lint`: every problem of a preset at once (preset/load_preset.h).
#include <algorithm>
#include <tuple>

#include "preset/load_preset.h"
#include "preset/preset_tree.h"
#include "preset/read_preset.h"

namespace rockbake {

std::vector<InputError> lintPreset(const std::filesystem::path& file, const PresetOverrides& overrides) {
  std::vector<InputError> problems;
  std::vector<std::string> files;  // in chain order, to list problems file by file
  try {
    PresetTree tree = readPresetTree(readPresetFile(file), file, overrides);
    for (const auto& origin : tree.source.origins)
      if (std::find(files.begin(), files.end(), origin.file) == files.end()) files.push_back(origin.file);
    tree.source.problems = &problems;
    readPreset(tree.root, tree.source, std::filesystem::absolute(file));
  } catch (const InputError& e) {
    problems.push_back(e);
  }
  const auto rank = [&](const InputError& e) {
    return std::tuple(std::size_t(std::find(files.begin(), files.end(), e.where().file) - files.begin()),
                      e.where().line, e.where().column);
  };
  std::stable_sort(problems.begin(), problems.end(),
                   [&](const InputError& a, const InputError& b) { return rank(a) < rank(b); });
  return problems;
}

}  // namespace rockbake
