// `rockbake lint`: every problem of a preset at once (preset/load_preset.h).
#include <algorithm>
#include <functional>
#include <tuple>

#include "preset/load_preset.h"
#include "preset/preset_tree.h"
#include "preset/read_preset.h"

namespace rockbake {

namespace {

std::vector<InputError> lintText(const std::function<std::string()>& text, const std::filesystem::path& file,
                                 const PresetOverrides& overrides) {
  std::vector<InputError> problems;
  std::vector<std::string> files;  // in chain order, to list problems file by file
  try {
    PresetTree tree = readPresetTree(text(), file, overrides);
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

}  // namespace

std::vector<InputError> lintPreset(const std::filesystem::path& file, const PresetOverrides& overrides) {
  return lintText([&] { return readPresetFile(file); }, file, overrides);
}

std::vector<InputError> lintBase(const std::filesystem::path& file, const PresetOverrides& overrides) {
  // Beside the base, so that `extends` finds it by its file name.
  const std::filesystem::path checker = std::filesystem::absolute(file).parent_path() / "(lint of a base)";
  std::string quoted;  // a YAML single-quoted scalar: ' doubled
  for (const char c : file.filename().string()) quoted += c == '\'' ? std::string("''") : std::string(1, c);
  const std::string text =
      "rockbake: 1\nextends: '" + quoted + "'\nname: base\nshape: {box: {size: [1, 1, 1]}}\ntime: 0.1\n";
  return lintText([&] { return text; }, checker, overrides);
}

}  // namespace rockbake
