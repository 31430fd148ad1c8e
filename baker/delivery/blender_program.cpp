#include "delivery/blender_program.h"

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <regex>
#include <sstream>

#include "core/error.h"
#include "platform/child_process.h"

namespace rockbake {

namespace fs = std::filesystem;

namespace {

const char* const kInstallHint =
    "install Blender: apt-get install blender (Debian's 3.4; scripts/setup.sh installs it too), or name it with "
    "--blender PATH or ROCKBAKE_BLENDER=PATH";

// `blender` in a folder of $PATH, as exec would find it; empty when none.
fs::path onPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / program;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

// The child's output until it closes it or `timeout` passes (then it is killed); its status.
BlenderRun readUntilExit(ChildProcess& child, std::chrono::seconds timeout) {
  constexpr std::size_t kKeep = 256 * 1024;
  BlenderRun run;
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + timeout;
  char buf[8192];
  while (true) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      run.timed_out = true;
      break;
    }
    pollfd p{child.output(), POLLIN, 0};
    const int r = poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
    if (r <= 0) continue;  // EINTR, or nothing yet
    const ssize_t n = read(child.output(), buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // EOF: it is exiting
    run.output.append(buf, std::size_t(n));
    if (run.output.size() > 2 * kKeep) run.output.erase(0, run.output.size() - kKeep);
  }
  if (run.timed_out) child.killGroup();
  child.closeOutput();
  run.exit_code = exitCode(child.wait());
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

ChildOptions commandLine(const fs::path& executable, std::vector<std::string> args) {
  ChildOptions options;
  args.insert(args.begin(), executable.string());
  options.argv = std::move(args);
  return options;
}

}  // namespace

BlenderProgram findBlender(const std::string& option) {
  const char* env = std::getenv("ROCKBAKE_BLENDER");
  const std::string named = !option.empty() ? option : (env && *env ? std::string(env) : std::string());
  const std::string origin = !option.empty()  ? "--blender " + option
                             : !named.empty() ? "ROCKBAKE_BLENDER=" + named
                                              : "blender on PATH";
  BlenderProgram blender;
  blender.executable = named.empty() ? onPath("blender") : fs::path(named);
  std::error_code ec;
  if (blender.executable.empty())
    throw InputError({"blender"}, "", "Blender is not installed: no blender on PATH", kInstallHint);
  if (!fs::exists(blender.executable, ec)) throw InputError({origin}, "", "there is no such file", kInstallHint);
  if (fs::is_directory(blender.executable, ec) || access(blender.executable.c_str(), X_OK) != 0)
    throw InputError({origin}, "", "is not an executable file", kInstallHint);
  std::optional<ChildProcess> child;
  try {
    child.emplace(commandLine(blender.executable, {"--version"}));
  } catch (const ChildStartError& e) {
    throw InputError({origin}, "", "cannot be run: " + e.reason, kInstallHint);
  }
  const BlenderRun run = readUntilExit(*child, std::chrono::seconds(60));
  std::smatch match;
  static const std::regex kVersion(R"((^|\n)Blender (\d+)\.(\d+)(\.\d+)?)");
  if (run.exit_code != 0 || !std::regex_search(run.output, match, kVersion))
    throw InputError({origin}, "", "is not Blender (`--version` did not say `Blender X.Y`)", kInstallHint);
  blender.major = std::stoi(match[2]);
  blender.minor = std::stoi(match[3]);
  blender.version = "Blender " + match[2].str() + "." + match[3].str() + match[4].str();
  if (blender.major < kMinBlenderMajor || (blender.major == kMinBlenderMajor && blender.minor < kMinBlenderMinor))
    throw InputError({origin}, "", "is " + blender.version + "; rockbake's Blender script needs 3.2 or newer",
                     kInstallHint);
  return blender;
}

BlenderRun runBlenderScript(const BlenderProgram& blender, const fs::path& script, const std::vector<std::string>& args,
                            int threads, std::chrono::seconds timeout) {
  std::vector<std::string> argv = {"--background",
                                   "--factory-startup",
                                   "-noaudio",
                                   "--threads",
                                   std::to_string(std::max(1, threads)),
                                   "--python-exit-code",
                                   "1",
                                   "--python",
                                   script.string(),
                                   "--"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::optional<ChildProcess> child;
  try {
    child.emplace(commandLine(blender.executable, argv));
  } catch (const ChildStartError& e) {
    throw std::runtime_error("cannot run " + blender.executable.string() + ": " + e.reason);
  }
  return readUntilExit(*child, timeout);
}

}  // namespace rockbake
