#include "platform/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace rockbake {
namespace {

void closeFd(int& fd) {
  if (fd >= 0) close(fd);
  fd = -1;
}

std::string stepName(ChildStartError::Step step) {
  switch (step) {
    case ChildStartError::Step::pipe:
      return "pipe failed";
    case ChildStartError::Step::fork:
      return "fork failed";
    case ChildStartError::Step::working_dir:
      return "cannot enter the working folder";
    case ChildStartError::Step::exec:
      return "cannot run it";
    case ChildStartError::Step::output_file:
      return "cannot open its output file";
  }
  return "";
}

// What the child reports through the close-on-exec pipe when a step before exec fails.
struct Report {
  ChildStartError::Step step;
  int error;
};

}  // namespace

ChildProcess::ChildProcess(const ChildOptions& options) : own_group_(options.own_group) {
  if (options.argv.empty()) throw std::invalid_argument("ChildProcess: no program to run");
  std::vector<char*> argv;
  for (const auto& s : options.argv) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  const std::string cwd = options.working_dir.string();
  const std::string out_file = options.output_file ? options.output_file->string() : std::string();

  int in_pipe[2] = {-1, -1}, out_pipe[2] = {-1, -1}, report[2] = {-1, -1};
  const auto fail = [&](ChildStartError::Step step, int e) {
    for (int* fd : {&in_pipe[0], &in_pipe[1], &out_pipe[0], &out_pipe[1], &report[0], &report[1]}) closeFd(*fd);
    throw ChildStartError(step, e, options.argv[0], stepName(step) + ": " + std::strerror(e));
  };
  if ((options.input_pipe && pipe2(in_pipe, O_CLOEXEC) != 0) ||
      (!options.output_file && pipe2(out_pipe, O_CLOEXEC) != 0) || pipe2(report, O_CLOEXEC) != 0)
    fail(ChildStartError::Step::pipe, errno);

  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) fail(ChildStartError::Step::fork, errno);
  if (pid == 0) {
    // Only async-signal-safe calls until exec.
    const auto die = [&](ChildStartError::Step step) {
      const Report r{step, errno};
      (void)!write(report[1], &r, sizeof r);
      _exit(127);
    };
    if (options.own_group) setpgid(0, 0);
    if (options.end_with_parent) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) _exit(127);  // the parent ended before the line above
    }
    // Close-on-exec like the pipes: the program gets fd 0 (dup2 clears the flag), not a spare.
    const int in = options.input_pipe ? in_pipe[0] : open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (in < 0 || dup2(in, 0) < 0) die(ChildStartError::Step::pipe);
    int out = out_pipe[1];
    if (!out_file.empty()) {
      out = open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (out < 0) die(ChildStartError::Step::output_file);
    }
    dup2(out, 1);
    dup2(out, 2);
    if (!cwd.empty() && chdir(cwd.c_str()) != 0) die(ChildStartError::Step::working_dir);
    execvp(argv[0], argv.data());
    die(ChildStartError::Step::exec);
  }
  pid_ = pid;
  closeFd(in_pipe[0]);
  closeFd(out_pipe[1]);
  closeFd(report[1]);
  // The report pipe closes on exec: end of file means the program is running.
  Report r{};
  ssize_t n;
  while ((n = read(report[0], &r, sizeof r)) < 0 && errno == EINTR) {
  }
  closeFd(report[0]);
  input_ = in_pipe[1];
  output_ = out_pipe[0];
  if (n == ssize_t(sizeof r)) {
    wait();
    closeInput();
    closeOutput();
    std::string reason = stepName(r.step);
    if (r.step == ChildStartError::Step::working_dir) reason += " " + cwd;
    if (r.step == ChildStartError::Step::output_file) reason += " " + out_file;
    throw ChildStartError(r.step, r.error, options.argv[0], reason + ": " + std::strerror(r.error));
  }
}

ChildProcess::~ChildProcess() {
  if (running()) {
    killGroup();
    wait();
  }
  closeInput();
  closeOutput();
}

void ChildProcess::closeInput() {
  closeFd(input_);
}
void ChildProcess::closeOutput() {
  closeFd(output_);
}

void ChildProcess::killGroup() {
  if (pid_ <= 0) return;
  // What it started may outlive it in its group, so the group is signalled even once it has
  // been reaped; the pid alone only before, when it cannot yet belong to another process.
  if (own_group_) kill(-pid_, SIGKILL);
  if (!status_) kill(pid_, SIGKILL);
}

int ChildProcess::wait() {
  if (status_) return *status_;
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  status_ = status;
  return status;
}

std::optional<int> ChildProcess::poll() {
  if (status_) return status_;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) status_ = status;
  return status_;
}

int exitCode(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace rockbake
