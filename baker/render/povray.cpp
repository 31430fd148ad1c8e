#include "render/povray.h"

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <sstream>
#include <string_view>
#include <thread>

#include "platform/child_process.h"

namespace rockbake {
namespace {

std::string tail(const std::string& text, int max_lines) {
  std::size_t pos = text.size();
  int lines = 0;
  while (pos > 0) {
    const std::size_t nl = text.rfind('\n', pos - 1);
    if (nl == std::string::npos) return text;
    if (nl + 1 < text.size() && ++lines > max_lines) return "...\n" + text.substr(nl + 1);
    pos = nl;
  }
  return text;
}

// What POV-Ray said that matters: what follows its last "====" section banner (the parse
// error, the render's own messages), not the forty lines of options it prints first; its last
// lines when it printed no banner.
std::string povrayWords(const std::string& messages) {
  std::size_t banner = std::string::npos;
  for (std::size_t at = messages.find("===="); at != std::string::npos; at = messages.find("====", at + 4))
    if (at == 0 || messages[at - 1] == '\n') banner = at;
  if (banner != std::string::npos) {
    const std::size_t after = messages.find('\n', banner);
    const std::string words = after == std::string::npos ? "" : messages.substr(after + 1);
    if (words.find_first_not_of(" \n") != std::string::npos) return tail(words, 30);
  }
  return tail(messages, 12);
}

std::string commandLine(const std::vector<std::string>& argv) {
  std::string s;
  for (const auto& a : argv) s += (s.empty() ? "" : " ") + a;
  return s;
}

}  // namespace

std::vector<std::string> povrayArguments(const PovrayJob& job) {
  std::ostringstream a;
  a << job.antialias;
  std::vector<std::string> argv = {
      job.executable, "-D", "-V", "-P", "+I" + job.scene.string(), "+O" + job.output.string(), "+FE",
      "+W" + std::to_string(job.width), "+H" + std::to_string(job.height), "+Q" + std::to_string(job.quality),
      job.antialias > 0 ? "+A" + a.str() : std::string("-A"),
      // Antialiasing jitter off: POV-Ray's jitter differs with the
      // thread that renders a block, so a jittered image changes
      // from run to run at any thread count above one
      // (docs/rendering.md, "Running POV-Ray").
      "-J", "+WT" + std::to_string(job.threads < 1 ? 1 : job.threads), "+BS" + std::to_string(kPovrayBlockRows)};
  if (job.end_row > 0) {
    argv.push_back("+SR" + std::to_string(job.first_row + 1));  // POV-Ray counts rows from 1
    argv.push_back("+ER" + std::to_string(job.end_row));
  }
  return argv;
}

namespace {

PovrayResult runPovrayOnce(const PovrayJob& job) {
  const std::vector<std::string> args = povrayArguments(job);
  const std::string cwd = job.working_dir.string();

  const auto start = std::chrono::steady_clock::now();
  std::optional<ChildProcess> child;
  try {
    ChildOptions options;
    options.argv = args;
    options.working_dir = job.working_dir;
    child.emplace(options);
  } catch (const ChildStartError& e) {
    if (e.step == ChildStartError::Step::working_dir)
      throw PovrayError("cannot run POV-Ray: cannot enter the asset folder " + cwd + ": " + std::strerror(e.error));
    if (e.step == ChildStartError::Step::exec && e.error == ENOENT)
      throw PovrayError("POV-Ray ('" + job.executable +
                        "') was not found on PATH; rendering needs it: install it with: apt-get install povray "
                        "(Debian package 'povray'), or bake with --no-render");
    if (e.step == ChildStartError::Step::exec)
      throw PovrayError("cannot run POV-Ray ('" + job.executable + "'): " + std::strerror(e.error));
    throw PovrayError("cannot run POV-Ray: " + e.reason);
  }

  std::string messages;
  constexpr std::size_t kKeep = 256 * 1024;
  bool timed_out = false, cancelled = false;
  const auto deadline = start + job.timeout;
  char buf[8192];
  while (true) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    if (job.cancel && job.cancel->load()) {
      cancelled = true;
      break;
    }
    pollfd p{child->output(), POLLIN, 0};
    const int r = poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) continue;
    const ssize_t n = read(child->output(), buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // EOF: POV-Ray closed its output (it is exiting)
    messages.append(buf, std::size_t(n));
    if (messages.size() > 2 * kKeep) messages.erase(0, messages.size() - kKeep);
  }
  if (timed_out || cancelled) child->killGroup();
  child->closeOutput();
  const int status = child->wait();
  PovrayResult result;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.messages = messages;

  const std::string where = "POV-Ray (" + commandLine(args) + ", in " + cwd + ")";
  if (cancelled) throw PovrayError(where + " was cancelled and killed");
  if (timed_out)
    throw PovrayError(where + " timed out after " + std::to_string(job.timeout.count()) +
                      " s and was killed; last messages:\n" + povrayWords(messages));
  if (WIFSIGNALED(status))
    throw PovrayError(where + " was killed by signal " + std::to_string(WTERMSIG(status)) + "; last messages:\n" +
                      povrayWords(messages));
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  // POV-Ray 3.7 reports parse errors on its output; be strict about both.
  const bool parse_error =
      messages.find("Parse Error") != std::string::npos || messages.find("Fatal error") != std::string::npos;
  if (code != 0 || parse_error)
    throw PovrayError(where + " failed (exit status " + std::to_string(code) + "); POV-Ray said:\n" +
                      povrayWords(messages));
  const auto out = job.output.is_absolute() ? job.output : job.working_dir / job.output;
  if (!std::filesystem::is_regular_file(out))
    throw PovrayError(where + " exited 0 but wrote no " + out.string() + "; POV-Ray said:\n" + povrayWords(messages));
  return result;
}

}  // namespace

PovrayResult runPovray(const PovrayJob& job) {
  // POV-Ray's front end gives its worker threads a few seconds to start and
  // otherwise gives up before reading the scene ("Timed out waiting for worker
  // thread startup"), which happens on a loaded machine; the render itself
  // would have been fine, so that one failure is retried.
  constexpr int kAttempts = 4;
  for (int attempt = 1;; ++attempt) {
    try {
      return runPovrayOnce(job);
    } catch (const PovrayError& e) {
      if (attempt == kAttempts || std::string_view(e.what()).find(kWorkerStartupTimeout) == std::string_view::npos)
        throw;
      std::this_thread::sleep_for(std::chrono::milliseconds(250 * attempt));
    }
  }
}

}  // namespace rockbake
