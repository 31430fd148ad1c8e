// The preset reader with `extends`: the input is a preset, optionally followed
// by "\n#==base==\n" and the text of the base preset it may extend as
// base.yaml (default: presets/base.yaml). loadPreset may refuse only with
// InputError, and lint must agree with it: no problems exactly when it loads.
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "preset/load_preset.h"

using namespace rockbake;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = fuzz::scratchDir("preset");
  static const std::string default_base =
      fuzz::readFile(std::filesystem::path(ROCKBAKE_SOURCE_DIR) / "presets/base.yaml");
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string marker = "\n#==base==\n";
  const std::size_t split = text.find(marker);
  const std::string preset = text.substr(0, split);
  fuzz::writeFile(dir / "base.yaml", split == std::string::npos ? default_base : text.substr(split + marker.size()));
  fuzz::writeFile(dir / "preset.yaml", preset);

  const bool loads = fuzz::refusesOnlyWith<InputError>([&] { loadPreset(dir / "preset.yaml"); });
  std::vector<InputError> problems;
  fuzz::refusesOnlyWith<InputError>([&] { problems = lintPreset(dir / "preset.yaml"); });
  if (loads != problems.empty())
    fuzz::finding(loads ? "lint reports '" + std::string(problems.front().what()) + "' for a preset that loads"
                        : "lint finds no problem in a preset that does not load");
  return 0;
}
