// The library file reader: parse, expand into jobs and split into shards.
// The folder holds rock.yaml and presets/cliff.yaml for entries to name. Only
// InputError may refuse a library.
#include <cstdint>
#include <string>

#include "core/error.h"
#include "fuzz_support.h"
#include "preset/library.h"

using namespace rockbake;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    const auto d = fuzz::scratchDir("library");
    std::filesystem::create_directories(d / "presets");
    fuzz::writeFile(d / "rock.yaml", "rockbake: 1\n");
    fuzz::writeFile(d / "presets/cliff.yaml", "rockbake: 1\n");
    return d;
  }();
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::refusesOnlyWith<InputError>([&] {
    const Library library = parseLibrary(text, dir / "lib.yaml");
    const auto jobs = expandLibrary(library);
    std::size_t total = 0;
    for (int n = 1; n <= 3; ++n)
      for (int i = 0; i < n; ++i) total += selectShard(jobs, {i, n}).size();
    if (total != 3 * jobs.size()) fuzz::finding("shards do not hold every job exactly once");
  });
  return 0;
}
