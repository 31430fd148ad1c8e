// How different two seeds of each catalogue preset are: the aligned
// intersection over union (sim/rock_measures.h) of their weathered rocks at resolution 48, with
// each preset's geology and with it removed (the altitude graph alone), in one
// run of one build.
//   rockbake_seed_iou [LIBRARY=presets/library.yaml] [RESOLUTION=48]
#include <cstdio>
#include <string>

#include "inputs/resolve_shape.h"
#include "preset/library.h"
#include "preset/load_preset.h"
#include "sim/rock_measures.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

namespace {

using namespace rockbake;

VoxelRock weathered(const Preset& p) {
  return weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
}

Preset withoutGeology(Preset p) {
  p.shape.variation.reset();
  p.durability.strata.reset();
  p.durability.joints.clear();
  p.durability.rind.reset();
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : std::string(ROCKBAKE_SOURCE_DIR) + "/presets/library.yaml";
  const int resolution = argc > 2 ? std::stoi(argv[2]) : 48;
  const Library library = loadLibrary(file);
  std::printf("| preset | seeds | IoU, no geology | IoU, geology |\n|---|---|---|---|\n");
  for (const LibraryEntry& entry : library.entries) {
    if (entry.seeds.size() < 2) continue;
    double iou[2];
    for (int geology = 0; geology < 2; ++geology) {
      VoxelRock rocks[2];
      for (std::size_t s = 0; s < 2; ++s) {
        const Preset p = loadPreset(entry.preset_file, {{}, entry.seeds[s], resolution});
        rocks[s] = weathered(geology ? p : withoutGeology(p));
      }
      iou[geology] = alignedIoU(rocks[0], rocks[1]);
    }
    std::printf("| %s | %llu, %llu | %.3f | %.3f |\n", entry.name.c_str(), (unsigned long long)entry.seeds[0],
                (unsigned long long)entry.seeds[1], iou[0], iou[1]);
  }
}
