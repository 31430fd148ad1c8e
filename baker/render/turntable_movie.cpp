#include "render/turntable_movie.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>

#include "render/preview.h"

namespace rockbake {
namespace {

std::string lastLines(const std::string& text, std::size_t max_chars) {
  if (text.size() <= max_chars) return text;
  const std::size_t nl = text.find('\n', text.size() - max_chars);
  return "...\n" + text.substr(nl == std::string::npos ? text.size() - max_chars : nl + 1);
}

// The frame padded to the movie's even size: the last column and row repeated.
std::string paddedRgb(const RgbImage& image, int width, int height) {
  std::string bytes(std::size_t(width) * std::size_t(height) * 3, '\0');
  for (int y = 0; y < height; ++y) {
    const int sy = std::min(y, image.height - 1);
    for (int x = 0; x < width; ++x) {
      const int sx = std::min(x, image.width - 1);
      const std::size_t s = (std::size_t(sy) * std::size_t(image.width) + std::size_t(sx)) * 3;
      const std::size_t d = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
      for (int c = 0; c < 3; ++c) bytes[d + std::size_t(c)] = char(image.pixels[s + std::size_t(c)]);
    }
  }
  return bytes;
}

// A helper program that is not on PATH (exec's ENOENT).
class ProgramNotFound : public MovieError {
 public:
  using MovieError::MovieError;
};

// FFmpeg as a child: we write its standard input to `in` and read its output
// and errors from `out`. A close-on-exec pipe carries errno back if exec fails.
struct Child {
  pid_t pid = -1;
  int in = -1, out = -1;
};

Child startFfmpeg(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& s : args) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  int in_pipe[2], out_pipe[2], report[2];
  if (pipe2(in_pipe, O_CLOEXEC) != 0 || pipe2(out_pipe, O_CLOEXEC) != 0 || pipe2(report, O_CLOEXEC) != 0)
    throw MovieError(std::string("cannot run FFmpeg: pipe failed: ") + std::strerror(errno));
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    const int e = errno;
    for (int fd : {in_pipe[0], in_pipe[1], out_pipe[0], out_pipe[1], report[0], report[1]}) close(fd);
    throw MovieError(std::string("cannot run FFmpeg: fork failed: ") + std::strerror(e));
  }
  if (pid == 0) {  // only async-signal-safe calls until exec
    setpgid(0, 0);
    // Its own process group keeps a Ctrl-C for the baker alone; the death
    // signal ends FFmpeg with the baker, killed or not, so none is left running.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    dup2(in_pipe[0], 0);
    dup2(out_pipe[1], 1);
    dup2(out_pipe[1], 2);
    execvp(argv[0], argv.data());
    const int e = errno;
    (void)!write(report[1], &e, sizeof e);
    _exit(127);
  }
  close(in_pipe[0]);
  close(out_pipe[1]);
  close(report[1]);
  int child_errno = 0;
  const bool exec_failed = read(report[0], &child_errno, sizeof child_errno) == sizeof child_errno;
  close(report[0]);
  if (exec_failed) {
    close(in_pipe[1]);
    close(out_pipe[0]);
    waitpid(pid, nullptr, 0);
    if (child_errno == ENOENT)
      throw ProgramNotFound("FFmpeg ('" + args[0] +
                            "') was not found on PATH; turntable movies need it: install it with: apt-get install "
                            "ffmpeg (Debian package 'ffmpeg'), or set render.turntable.frames: 0");
    throw MovieError("cannot run FFmpeg ('" + args[0] + "'): " + std::strerror(child_errno));
  }
  return {pid, in_pipe[1], out_pipe[0]};
}

// Writes all of `bytes`; false when FFmpeg closed its input (it failed).
// SIGPIPE is blocked on this thread meanwhile, and a pending one consumed,
// so a dead FFmpeg is an error message rather than the end of the baker.
bool writeAll(int fd, const std::string& bytes) {
  sigset_t pipe_set, old;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old);
  std::size_t done = 0;
  bool ok = true;
  while (done < bytes.size()) {
    const ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ok = false;
      break;
    }
    done += std::size_t(n);
  }
  if (!ok) {
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_set, nullptr, &zero) > 0) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return ok;
}

// Kills FFmpeg's process group when it makes no progress for kFfmpegStallSeconds
// (a frame not taken, or no exit once its input is closed) or the cancel flag
// is set, whichever comes first; checked every 100 ms while FFmpeg runs, so a
// Ctrl-C does not wait for the next frame.
class Watchdog {
 public:
  Watchdog(pid_t group, const std::atomic<bool>* cancel) : group_(group), cancel_(cancel) {
    progress();
    thread_ = std::thread([this] { watch(); });
  }
  ~Watchdog() {
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  void progress() {
    std::lock_guard lock(mutex_);
    deadline_ = std::chrono::steady_clock::now() + std::chrono::seconds(kFfmpegStallSeconds);
  }
  bool stalled() const { return stalled_; }
  bool cancelled() const { return cancelled_; }

 private:
  void watch() {
    std::unique_lock lock(mutex_);
    while (!done_) {
      wake_.wait_for(lock, std::chrono::milliseconds(100));
      if (done_) break;
      const bool cancel = cancel_ && cancel_->load();
      if (cancel || std::chrono::steady_clock::now() > deadline_) {
        (cancel ? cancelled_ : stalled_) = true;
        kill(-group_, SIGKILL);
        break;
      }
    }
  }
  pid_t group_;
  const std::atomic<bool>* cancel_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::chrono::steady_clock::time_point deadline_;
  bool done_ = false;
  std::atomic<bool> stalled_{false}, cancelled_{false};
  std::thread thread_;
};

// What FFmpeg wrote is an MP4 when its first box is `ftyp` (ISO/IEC 14496-12 §4.3).
bool startsWithFtyp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char head[8] = {};
  return in.read(head, sizeof head) && std::string_view(head + 4, 4) == "ftyp";
}

// The ffprobe of the same FFmpeg: the path's sibling, or ffprobe on PATH.
std::string ffprobeFor(const std::string& ffmpeg) {
  const std::filesystem::path path(ffmpeg);
  return path.has_parent_path() ? (path.parent_path() / "ffprobe").string() : std::string("ffprobe");
}

// Why ffprobe does not vouch for `file` holding `frames` video frames: empty when it decodes
// exactly that many, or when there is no ffprobe on PATH to ask (the ftyp check then stands
// alone). Anything else it does (fails, hangs, answers no number) refuses the movie. Bounded like
// FFmpeg: killed with its group when it says nothing for kFfmpegStallSeconds or `cancel` is set.
std::string frameCountProblem(const std::string& ffprobe, const std::filesystem::path& file, std::size_t frames,
                              const std::atomic<bool>* cancel) {
  Child child;
  try {
    child = startFfmpeg({ffprobe, "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                         "stream=nb_read_frames", "-of", "csv=p=0", file.string()});
  } catch (const ProgramNotFound&) {
    return "";
  }
  close(child.in);
  std::string said;
  int status = 0;
  bool stalled = false, cancelled = false;
  {
    Watchdog watchdog(child.pid, cancel);
    char buf[1024];
    while (true) {
      const ssize_t n = read(child.out, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      if (said.size() < 4096) said.append(buf, std::size_t(n));
      watchdog.progress();
    }
    // Reaped under the watchdog too: an ffprobe that closed its output and hangs is killed.
    while (waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
    }
    stalled = watchdog.stalled(), cancelled = watchdog.cancelled();
  }
  close(child.out);
  if (cancelled) return "ffprobe, counting its frames, was cancelled and killed";
  if (stalled)
    return "ffprobe, counting its frames, made no progress for " + std::to_string(kFfmpegStallSeconds) + " s";
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return "ffprobe cannot read it: " + lastLines(said, 2000);
  std::size_t used = 0;
  long counted = -1;
  try {
    counted = std::stol(said, &used);
  } catch (const std::exception&) {
  }
  if (counted < 0 || said.find_first_not_of(" \r\n", used) != std::string::npos)
    return "ffprobe counts no frames in it: " + lastLines(said, 2000);
  if (std::size_t(counted) != frames)
    return "it holds " + std::to_string(counted) + " frames, not the " + std::to_string(frames) +
           " it was given (ffprobe's count)";
  return "";
}

}  // namespace

std::array<int, 2> movieFrameSize(int width, int height) {
  return {width + (width & 1), height + (height & 1)};
}

std::vector<std::string> ffmpegArguments(const TurntableMovieJob& job, int width, int height,
                                         const std::filesystem::path& output) {
  const std::string fps = std::to_string(job.fps);
  return {job.executable, "-hide_banner", "-nostats", "-loglevel", "error", "-y",
          // The frames, display-referred sRGB bytes, on standard input.
          "-f", "rawvideo", "-pix_fmt", "rgb24", "-video_size", std::to_string(width) + "x" + std::to_string(height),
          "-framerate", fps, "-i", "pipe:0",
          // BT.709 limited range 4:2:0, as review tools and browsers expect, and tagged so.
          "-vf", "scale=out_color_matrix=bt709:out_range=tv:flags=accurate_rnd+full_chroma_int+bitexact,format=yuv420p",
          "-c:v", "libx264", "-profile:v", "high", "-preset", "medium", "-crf", "18", "-g", fps, "-threads", "1",
          "-colorspace", "bt709", "-color_primaries", "bt709", "-color_trc", "iec61966-2-1", "-color_range", "tv",
          // No time stamps, encoder strings or copied metadata: the same frames give the same bytes.
          "-map_metadata", "-1", "-fflags", "+bitexact", "-flags:v", "+bitexact", "-movflags", "+faststart", "-f",
          "mp4", output.string()};
}

void writeTurntableMovie(const TurntableMovieJob& job) {
  if (job.frames.empty()) throw MovieError("a turntable movie needs at least one frame");
  const RgbImage first = exrToDisplay(job.frames.front(), job.ocio_config);
  const auto [width, height] = movieFrameSize(first.width, first.height);
  const std::filesystem::path tmp = job.target.parent_path() / ("." + job.target.stem().string() + ".ffmpeg.mp4");
  const std::vector<std::string> args = ffmpegArguments(job, width, height, tmp);
  Child child = startFfmpeg(args);
  std::optional<Watchdog> watchdog(std::in_place, child.pid, job.cancel);

  std::string messages;
  std::thread reader([&] {
    char buf[4096];
    while (true) {
      const ssize_t n = read(child.out, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      messages.append(buf, std::size_t(n));
      if (messages.size() > 256 * 1024) messages.erase(0, messages.size() - 128 * 1024);
    }
  });
  std::string failure;  // ours, not FFmpeg's
  bool cancelled = false;
  for (std::size_t i = 0; i < job.frames.size() && failure.empty(); ++i) {
    if (job.cancel && job.cancel->load()) {
      cancelled = true;
      break;
    }
    try {
      const RgbImage frame = i == 0 ? first : exrToDisplay(job.frames[i], job.ocio_config);
      if (frame.width != first.width || frame.height != first.height)
        failure = job.frames[i].string() + " is " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                  ", the first frame " + std::to_string(first.width) + "x" + std::to_string(first.height);
      else if (!writeAll(child.in, paddedRgb(frame, width, height)))
        break;  // FFmpeg stopped reading (or was killed): its status and messages say why
      watchdog->progress();
    } catch (const std::exception& e) {
      failure = e.what();
    }
  }
  if (cancelled || !failure.empty()) kill(-child.pid, SIGKILL);
  close(child.in);
  int status = 0;
  while (waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
  }
  const bool stalled = watchdog->stalled();
  cancelled = cancelled || watchdog->cancelled();
  watchdog.reset();
  kill(-child.pid, SIGKILL);  // anything FFmpeg started that outlived it
  reader.join();
  close(child.out);

  std::error_code ec;
  const std::string where = "FFmpeg (writing " + job.target.string() + ")";
  const bool exited = !cancelled && !stalled && failure.empty() && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  const bool ok = exited && std::filesystem::is_regular_file(tmp, ec) && startsWithFtyp(tmp);
  if (!ok) std::filesystem::remove(tmp, ec);
  if (cancelled) throw MovieError(where + " was cancelled and killed");
  if (stalled)
    throw MovieError(where + " made no progress for " + std::to_string(kFfmpegStallSeconds) +
                     " s and was killed; check that `" + job.executable +
                     " -version` answers, or set render.turntable.frames: 0. FFmpeg said:\n" +
                     lastLines(messages, 4000));
  if (exited && !ok)
    throw MovieError(where + " exited 0 but wrote no MP4 (no ftyp box at its start); nothing was kept: check that `" +
                     job.executable + "` is FFmpeg (`" + job.executable + " -version`). It said:\n" +
                     lastLines(messages, 4000));
  if (!failure.empty()) throw MovieError("cannot make " + job.target.string() + ": " + failure);
  if (!ok)
    throw MovieError(where + " failed (" +
                     (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                          : "exit status " + std::to_string(WEXITSTATUS(status))) +
                     "); FFmpeg said:\n" + lastLines(messages, 4000));
  // An MP4 with fewer (or more) frames than were sent, or one ffprobe cannot read, is no turntable.
  if (const std::string problem = frameCountProblem(ffprobeFor(job.executable), tmp, job.frames.size(), job.cancel);
      !problem.empty()) {
    std::filesystem::remove(tmp, ec);
    throw MovieError(where + " exited 0, but " + problem + "; nothing was kept. FFmpeg said:\n" +
                     lastLines(messages, 4000));
  }
  std::filesystem::rename(tmp, job.target, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw MovieError("cannot write " + job.target.string() + ": " + ec.message());
  }
}

}  // namespace rockbake
