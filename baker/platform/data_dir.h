// Where rockbake finds the files it ships beside its executable (docs/architecture.md,
// "Finding data"): the render templates with the OpenColorIO config, the studio page with
// its pinned three.js, and any later page. They sit in one folder, the data folder:
//   - $ROCKBAKE_DATA_DIR, when it is set and not empty;
//   - else <the running executable's folder>/../share/rockbake, the executable found
//     through /proc/self/exe. Installed, <prefix>/bin/rockbake reads <prefix>/share/rockbake;
//     in the build tree, build/baker/rockbake (and build/tests/…) read build/share/rockbake,
//     which the build fills with links to the source tree (cmake/Install.cmake).
// No path is compiled in, so a moved, packaged or shared-disk install finds its data the
// same way. Nothing here caches the environment: each call reads it again.
#pragma once

#include <filesystem>
#include <string>

namespace rockbake {

// The data folder, as above. Never throws; the folder may not exist (see requireDataPath).
// Empty only when ROCKBAKE_DATA_DIR is unset and the executable cannot be found.
std::filesystem::path dataDir();

// How dataDir() was chosen, for messages: "ROCKBAKE_DATA_DIR=/x" or
// "beside the executable /x/bin/rockbake".
std::string dataDirOrigin();

// dataDir() / relative, when it exists. Otherwise throws std::runtime_error naming the
// missing path, how the data folder was chosen and what to do (set ROCKBAKE_DATA_DIR,
// reinstall, or in a build tree configure again).
std::filesystem::path requireDataPath(const std::filesystem::path& relative);

}  // namespace rockbake
