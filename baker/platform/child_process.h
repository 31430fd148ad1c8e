// A program run as a child process: the one way rockbake starts POV-Ray, FFmpeg and
// ffprobe (and the tests start rockbake). The child runs in its own process group, so a
// Ctrl-C at the terminal reaches the baker alone and killGroup() takes anything the child
// started with it; with `end_with_parent` it is killed when the thread that started it
// ends, so no child outlives a killed baker. Its standard output and error go to one
// pipe (or to a file); its standard input is a pipe or /dev/null.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockbake {

struct ChildOptions {
  std::vector<std::string> argv;      // argv[0] is looked up on PATH when it has no slash
  std::filesystem::path working_dir;  // empty: this process's
  bool input_pipe = false;            // false: standard input is /dev/null
  // Standard output and error written to this file (created, or truncated) instead of a pipe.
  std::optional<std::filesystem::path> output_file;
  bool own_group = true;        // its own process group (setpgid)
  bool end_with_parent = true;  // SIGKILL when the starting thread ends (PR_SET_PDEATHSIG)
};

// The child could not be started: `error` is the errno of the step that failed
// (ENOENT from exec: the program is not on PATH); `reason` says which step and why,
// what() the same after the program's name.
class ChildStartError : public std::runtime_error {
 public:
  enum class Step { pipe, fork, working_dir, exec, output_file };
  ChildStartError(Step step, int error, const std::string& program, const std::string& reason)
      : std::runtime_error(program + ": " + reason), step(step), error(error), reason(reason) {}
  Step step;
  int error;
  std::string reason;
};

class ChildProcess {
 public:
  // Starts the program; returns once exec has succeeded, else throws ChildStartError.
  explicit ChildProcess(const ChildOptions& options);
  // A child still running is killed with its group and reaped; the pipes are closed.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  int input() const { return input_; }    // write end of its standard input; -1 when closed or none
  int output() const { return output_; }  // read end of its output and errors; -1 when closed or none
  void closeInput();
  void closeOutput();

  // SIGKILL to its process group (or to it alone without one); harmless once it has been reaped.
  void killGroup();
  // Waits for it to end and returns the status as waitpid gives it (EINTR retried).
  int wait();
  // The status if it has ended, without waiting.
  std::optional<int> poll();
  bool running() const { return !status_.has_value(); }

 private:
  pid_t pid_ = -1;
  bool own_group_ = true;
  int input_ = -1, output_ = -1;
  std::optional<int> status_;
};

// Exit status 0..255 for a status that says the child exited, -1 when a signal ended it.
int exitCode(int status);

}  // namespace rockbake
