// Blender, run as its own process for `rockbake blender-library` (docs/libraries.md, "Blender's
// asset browser"): never linked, found on PATH or named, its version checked once, then a
// script run in the background, one process per asset. The child starts through
// platform/child_process.h, so it dies with the thread that started it and its output is read
// under a time limit.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace rockbake {

// The oldest Blender the script runs on: `bpy.context.temp_override` came in 3.2. Tested with
// Debian 12's 3.4.
inline constexpr int kMinBlenderMajor = 3;
inline constexpr int kMinBlenderMinor = 2;

struct BlenderProgram {
  std::filesystem::path executable;  // the file run
  std::string version;               // "Blender 3.4.1"
  int major = 0, minor = 0;
};

// The Blender to run: `option` (--blender PATH) when not empty, else $ROCKBAKE_BLENDER when set and
// not empty, else `blender` on PATH; run once with --version. Throws InputError (exit status 2)
// when it is missing (naming where it looked and what to install: `apt-get install blender`, or
// scripts/setup.sh), cannot be run, does not say it is Blender, or is older than 3.2.
BlenderProgram findBlender(const std::string& option);

struct BlenderRun {
  int exit_code = -1;  // -1: ended by a signal, or killed at the time limit
  bool timed_out = false;
  double seconds = 0.0;
  std::string output;  // its standard output and error together (the last 256 KiB)
};

// `blender --background --factory-startup -noaudio --threads N --python-exit-code 1
//  --python SCRIPT -- ARGS...`: the script's own failure is exit status 1. Throws
// std::runtime_error when Blender cannot be started.
BlenderRun runBlenderScript(const BlenderProgram& blender, const std::filesystem::path& script,
                            const std::vector<std::string>& args, int threads, std::chrono::seconds timeout);

}  // namespace rockbake
