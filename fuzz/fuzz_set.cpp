// --set parsing: each line of the input is one `--set key.path=VALUE`
// argument (at most 8), applied to a small valid preset. Only InputError may
// refuse them.
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_support.h"
#include "preset/load_preset.h"

using namespace rockbake;

namespace {
const char* const kPreset = R"(rockbake: 1
name: small
seed: 3
grid: {size: [2.0, 2.0, 2.0], resolution: 24}
shape:
  box: {size: [1.5, 1.5, 1.5]}
bubbles:
  - up_to: 1.0
    bubble: {sphere: {radius: 0.3}}
    spheroidal: 1.0
    cavernous: 0.2
durability:
  points: [[0, 1], [0.5, 2], [1, 1]]
  noise: [null, {amplitude: 0.2, period: 0.5}]
time: 0.5
)";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = fuzz::scratchDir("set");
  PresetOverrides overrides;
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
  for (std::string line; std::getline(lines, line) && overrides.sets.size() < 8;) overrides.sets.push_back(line);
  fuzz::refusesOnlyWith<InputError>([&] { parsePreset(kPreset, dir / "small.yaml", overrides); });
  return 0;
}
