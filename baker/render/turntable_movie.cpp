#include "render/turntable_movie.h"

#include <pthread.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>

#include "platform/child_process.h"
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

// FFmpeg (or ffprobe) as a child: we write its standard input and read its output and errors.
std::unique_ptr<ChildProcess> startFfmpeg(const std::vector<std::string>& args) {
  try {
    ChildOptions options;
    options.argv = args;
    options.input_pipe = true;
    return std::make_unique<ChildProcess>(options);
  } catch (const ChildStartError& e) {
    if (e.step == ChildStartError::Step::exec && e.error == ENOENT)
      throw ProgramNotFound("FFmpeg ('" + args[0] +
                            "') was not found on PATH; turntable movies need it: install it with: apt-get install "
                            "ffmpeg (Debian package 'ffmpeg'), or set render.turntable.frames: 0");
    if (e.step == ChildStartError::Step::exec)
      throw MovieError("cannot run FFmpeg ('" + args[0] + "'): " + std::strerror(e.error));
    throw MovieError("cannot run FFmpeg: " + e.reason);
  }
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
  std::unique_ptr<ChildProcess> child;
  try {
    child = startFfmpeg({ffprobe, "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                         "stream=nb_read_frames", "-of", "csv=p=0", file.string()});
  } catch (const ProgramNotFound&) {
    return "";
  }
  child->closeInput();
  std::string said;
  int status = 0;
  bool stalled = false, cancelled = false;
  {
    Watchdog watchdog(child->pid(), cancel);
    char buf[1024];
    while (true) {
      const ssize_t n = read(child->output(), buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      if (said.size() < 4096) said.append(buf, std::size_t(n));
      watchdog.progress();
    }
    // Reaped under the watchdog too: an ffprobe that closed its output and hangs is killed.
    status = child->wait();
    stalled = watchdog.stalled(), cancelled = watchdog.cancelled();
  }
  child->closeOutput();
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
  const std::unique_ptr<ChildProcess> child = startFfmpeg(args);
  std::optional<Watchdog> watchdog(std::in_place, child->pid(), job.cancel);

  std::string messages;
  std::thread reader([&] {
    char buf[4096];
    while (true) {
      const ssize_t n = read(child->output(), buf, sizeof buf);
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
      else if (!writeAll(child->input(), paddedRgb(frame, width, height)))
        break;  // FFmpeg stopped reading (or was killed): its status and messages say why
      watchdog->progress();
    } catch (const std::exception& e) {
      failure = e.what();
    }
  }
  if (cancelled || !failure.empty()) child->killGroup();
  child->closeInput();
  const int status = child->wait();
  const bool stalled = watchdog->stalled();
  cancelled = cancelled || watchdog->cancelled();
  watchdog.reset();
  child->killGroup();  // anything FFmpeg started that outlived it
  reader.join();
  child->closeOutput();

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
