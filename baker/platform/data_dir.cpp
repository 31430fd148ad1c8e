#include "platform/data_dir.h"

#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace rockbake {
namespace {

// The running executable, symlinks resolved; empty where /proc is not mounted. It cannot
// change while the process runs, so it is read once.
const std::filesystem::path& executablePath() {
  static const std::filesystem::path path = [] {
    std::error_code ec;
    std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::filesystem::path() : exe;
  }();
  return path;
}

const char* configuredDataDir() {
  const char* value = std::getenv("ROCKBAKE_DATA_DIR");
  return value && *value ? value : nullptr;
}

}  // namespace

std::filesystem::path dataDir() {
  if (const char* configured = configuredDataDir()) return configured;
  const std::filesystem::path& exe = executablePath();
  if (exe.empty()) return {};
  return exe.parent_path().parent_path() / "share" / "rockbake";
}

std::string dataDirOrigin() {
  if (const char* configured = configuredDataDir()) return std::string("ROCKBAKE_DATA_DIR=") + configured;
  if (executablePath().empty()) return "no executable path (/proc/self/exe cannot be read)";
  return "beside the executable " + executablePath().string();
}

std::filesystem::path requireDataPath(const std::filesystem::path& relative) {
  const std::filesystem::path dir = dataDir();
  if (dir.empty())
    throw std::runtime_error(
        "cannot find rockbake's data folder: /proc/self/exe cannot be read, so the executable's own folder is "
        "unknown; set ROCKBAKE_DATA_DIR to the installed <prefix>/share/rockbake");
  const std::filesystem::path path = dir / relative;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) return path;
  const std::string hint =
      configuredDataDir()
          ? "set ROCKBAKE_DATA_DIR to an installed <prefix>/share/rockbake, or unset it to use the one beside "
            "the executable"
          : "keep bin/rockbake and share/rockbake/ of an install together (cmake --install lays both out; in a "
            "build tree, configure again), or set ROCKBAKE_DATA_DIR to an installed <prefix>/share/rockbake";
  throw std::runtime_error("rockbake's data is missing " + path.string() + " (data folder " + dir.string() + ", " +
                           dataDirOrigin() + "): " + hint);
}

}  // namespace rockbake
