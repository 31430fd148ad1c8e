// Child processes (platform/child_process.h), with real programs: their output
// through the pipe or into a file, a round trip through standard input, start
// failures with the step and errno, the exit status, killGroup() taking what the
// child started, and no child left running or unreaped.
#include "platform/child_process.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "test_support.h"

namespace rockbake {
namespace {

using namespace std::chrono_literals;

ChildOptions options(std::vector<std::string> argv) {
  ChildOptions o;
  o.argv = std::move(argv);
  return o;
}

// Everything read from `fd` until end of file.
std::string readAll(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, std::size_t(n));
  }
  return text;
}

// One line read from `fd`, a byte at a time, without its newline.
std::string readLine(int fd) {
  std::string line;
  for (char c = 0; ::read(fd, &c, 1) == 1 && c != '\n';) line += c;
  return line;
}

// True once no process `pid` is running: gone (ESRCH), or a zombie left to whoever
// reaps orphans here (in a container that may never happen).
bool endsWithin(pid_t pid, std::chrono::milliseconds limit) {
  const auto until = std::chrono::steady_clock::now() + limit;
  for (;;) {
    if (::kill(pid, 0) != 0 && errno == ESRCH) return true;
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string text;
    std::getline(stat, text);
    const std::size_t paren = text.rfind(')');
    if (paren != std::string::npos && paren + 2 < text.size() && (text[paren + 2] == 'Z' || text[paren + 2] == 'X'))
      return true;
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(10ms);
  }
}

// The ChildStartError a start throws; nullopt when it started.
std::optional<ChildStartError> startError(const ChildOptions& o) {
  try {
    ChildProcess child(o);
  } catch (const ChildStartError& e) {
    return e;
  }
  return std::nullopt;
}

TEST(ChildProcess, OutputAndErrorsComeThroughOnePipe) {
  ChildProcess child(options({"/bin/sh", "-c", "echo out; echo err >&2"}));
  ASSERT_GE(child.output(), 0);
  EXPECT_EQ(child.input(), -1) << "standard input is /dev/null unless asked for";
  EXPECT_EQ(readAll(child.output()), "out\nerr\n");
  const int status = child.wait();
  EXPECT_TRUE(WIFEXITED(status));
  EXPECT_EQ(exitCode(status), 0);
  EXPECT_FALSE(child.running());
}

TEST(ChildProcess, InputPipeRoundTrip) {
  ChildOptions o = options({"cat"});  // found on PATH
  o.input_pipe = true;
  ChildProcess child(o);
  ASSERT_GE(child.input(), 0);
  const std::string text = "a line\nand another, with no newline";
  ASSERT_EQ(::write(child.input(), text.data(), text.size()), ssize_t(text.size()));
  child.closeInput();
  EXPECT_EQ(child.input(), -1);
  EXPECT_EQ(readAll(child.output()), text);
  EXPECT_EQ(exitCode(child.wait()), 0);
}

// This process's standard input replaced by `fd` for the object's life.
class StandardInputFrom {
 public:
  explicit StandardInputFrom(int fd) : saved_(::dup(0)) { ::dup2(fd, 0); }
  ~StandardInputFrom() {
    ::dup2(saved_, 0);
    ::close(saved_);
  }
  StandardInputFrom(const StandardInputFrom&) = delete;
  StandardInputFrom& operator=(const StandardInputFrom&) = delete;

 private:
  int saved_;
};

TEST(ChildProcess, StandardInputIsDevNullWithoutAPipe) {
  // Standard input a pipe here while the child starts, so that inheriting it would show.
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  std::unique_ptr<ChildProcess> child;
  {
    const StandardInputFrom pipe_input(fds[0]);
    child = std::make_unique<ChildProcess>(options({"/bin/sh", "-c", "readlink /proc/self/fd/0"}));
  }
  ::close(fds[0]);
  ::close(fds[1]);
  EXPECT_EQ(readAll(child->output()), "/dev/null\n");
  EXPECT_EQ(exitCode(child->wait()), 0);
}

TEST(ChildProcess, AProgramNotOnPathThrowsAtExecWithEnoent) {
  const auto error = startError(options({"rockbake-test-no-such-program"}));
  ASSERT_TRUE(error.has_value()) << "it started";
  EXPECT_EQ(error->step, ChildStartError::Step::exec);
  EXPECT_EQ(error->error, ENOENT);
  EXPECT_NE(std::string(error->what()).find("rockbake-test-no-such-program"), std::string::npos) << error->what();
}

TEST(ChildProcess, AMissingWorkingFolderThrowsAtWorkingDir) {
  test::TempDir dir;
  ChildOptions o = options({"/bin/sh", "-c", "exit 0"});
  o.working_dir = dir.path() / "missing";
  const auto error = startError(o);
  ASSERT_TRUE(error.has_value()) << "it started";
  EXPECT_EQ(error->step, ChildStartError::Step::working_dir);
  EXPECT_EQ(error->error, ENOENT);
  EXPECT_NE(std::string(error->what()).find((dir.path() / "missing").string()), std::string::npos) << error->what();
}

TEST(ChildProcess, RunsInItsWorkingFolder) {
  test::TempDir dir;
  ChildOptions o = options({"/bin/sh", "-c", "pwd -P"});
  o.working_dir = dir.path();
  ChildProcess child(o);
  EXPECT_EQ(readAll(child.output()), std::filesystem::canonical(dir.path()).string() + "\n");
  EXPECT_EQ(exitCode(child.wait()), 0);
}

TEST(ChildProcess, ExitCodeIsTheExitStatusOrMinusOneForASignal) {
  ChildProcess seven(options({"/bin/sh", "-c", "exit 7"}));
  EXPECT_EQ(exitCode(seven.wait()), 7);
  EXPECT_EQ(exitCode(seven.wait()), 7) << "a second wait gives the same status";
  ChildProcess killed(options({"/bin/sh", "-c", "kill -9 $$"}));
  const int status = killed.wait();
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  EXPECT_EQ(exitCode(status), -1);
}

TEST(ChildProcess, PollSaysNothingWhileItRuns) {
  ChildOptions o = options({"cat"});
  o.input_pipe = true;
  ChildProcess child(o);
  EXPECT_FALSE(child.poll().has_value());
  EXPECT_TRUE(child.running());
  child.closeInput();  // cat ends
  std::optional<int> status;
  for (int i = 0; i < 500 && !status; ++i) {
    status = child.poll();
    if (!status) std::this_thread::sleep_for(10ms);
  }
  ASSERT_TRUE(status.has_value()) << "cat did not end at end of file";
  EXPECT_EQ(exitCode(*status), 0);
  EXPECT_EQ(child.wait(), *status);
}

// A shell in the child's group starts a background sleep (printing its pid) and sleeps
// itself: killGroup() ends both, not the shell alone.
TEST(ChildProcess, KillGroupKillsTheChildAndWhatItStarted) {
  ChildProcess child(options({"/bin/sh", "-c", "sleep 30 & echo $!; sleep 30"}));
  const std::string line = readLine(child.output());
  ASSERT_FALSE(line.empty()) << "the shell printed no pid";
  const pid_t grandchild = pid_t(std::stol(line));
  EXPECT_EQ(::getpgid(grandchild), child.pid()) << "the child leads its own process group";
  EXPECT_NE(::getpgid(0), child.pid());
  const auto start = std::chrono::steady_clock::now();
  child.killGroup();
  const int status = child.wait();
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  EXPECT_LT(std::chrono::steady_clock::now() - start, 10s);
  const bool ended = endsWithin(grandchild, 5s);
  EXPECT_TRUE(ended) << "the background sleep " << grandchild << " outlived killGroup()";
  if (!ended) ::kill(grandchild, SIGKILL);
  child.killGroup();  // harmless once reaped
}

TEST(ChildProcess, WithoutItsOwnGroupItStaysInThisOne) {
  ChildOptions o = options({"sleep", "30"});
  o.own_group = false;
  ChildProcess child(o);
  EXPECT_EQ(::getpgid(child.pid()), ::getpgid(0));
  child.killGroup();
  const int status = child.wait();
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
}

TEST(ChildProcess, AnOutputFileTakesBothStreams) {
  test::TempDir dir;
  const std::filesystem::path log = dir.path() / "child.log";
  test::writeText(log, "left from before, and longer than what the child writes\n");  // truncated
  ChildOptions o = options({"/bin/sh", "-c", "echo out; echo err >&2; echo out again"});
  o.output_file = log;
  ChildProcess child(o);
  EXPECT_EQ(child.output(), -1) << "no pipe when the output goes to a file";
  EXPECT_EQ(exitCode(child.wait()), 0);
  EXPECT_EQ(test::readBytes(log), "out\nerr\nout again\n");
}

TEST(ChildProcess, AnOutputFileThatCannotBeOpenedThrows) {
  test::TempDir dir;
  ChildOptions o = options({"/bin/sh", "-c", "exit 0"});
  o.output_file = dir.path() / "missing" / "child.log";
  const auto error = startError(o);
  ASSERT_TRUE(error.has_value()) << "it started";
  EXPECT_EQ(error->step, ChildStartError::Step::output_file);
  EXPECT_EQ(error->error, ENOENT);
}

TEST(ChildProcess, TheDestructorKillsAndReapsARunningChild) {
  pid_t pid = -1;
  const auto start = std::chrono::steady_clock::now();
  {
    ChildProcess child(options({"sleep", "30"}));
    pid = child.pid();
    ASSERT_GT(pid, 0);
    EXPECT_EQ(::kill(pid, 0), 0) << "it runs";
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 10s) << "the destructor waited for the sleep to end";
  int status = 0;
  errno = 0;
  EXPECT_EQ(::waitpid(pid, &status, WNOHANG), -1) << "the child is still this process's to reap";
  EXPECT_EQ(errno, ECHILD);
}

// end_with_parent: SIGKILL when the thread that started the child ends, though the
// ChildProcess itself lives on.
TEST(ChildProcess, EndsWithTheThreadThatStartedIt) {
  std::unique_ptr<ChildProcess> child;
  std::thread([&] { child = std::make_unique<ChildProcess>(options({"sleep", "30"})); }).join();
  ASSERT_NE(child, nullptr);
  std::optional<int> status;
  for (int i = 0; i < 500 && !status; ++i) {
    status = child->poll();
    if (!status) std::this_thread::sleep_for(10ms);
  }
  ASSERT_TRUE(status.has_value()) << "the child outlived the thread that started it";
  EXPECT_TRUE(WIFSIGNALED(*status));
  EXPECT_EQ(WTERMSIG(*status), SIGKILL);
}

}  // namespace
}  // namespace rockbake
