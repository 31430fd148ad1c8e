#include "cli/library_progress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace rockbake {
namespace {

using Clock = std::chrono::steady_clock;

std::string clockText(double seconds) {
  const long s = long(std::lround(std::max(0.0, seconds)));
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                   : fmt::format("{}:{:02}", s / 60, s % 60);
}

}  // namespace

// Progress and ETA: one status line redrawn in place on a terminal, plain log
// lines otherwise. Called from the pipeline's threads.
class LibraryProgress::Display {
 public:
  // Log lines go through a copy of the default logger kept at info level, so they show while the
  // jobs' own logs are turned down.
  Display(std::size_t total, int jobs, bool terminal, const std::atomic<bool>* cancel)
      : total_(total),
        jobs_(jobs),
        terminal_(terminal),
        cancel_(cancel),
        log_(spdlog::default_logger()->clone("library")) {
    log_->set_level(spdlog::level::info);
    // On a terminal the status line also ticks between events, so elapsed time and ETA stay current.
    if (terminal_)
      ticker_ = std::thread([this] {
        std::unique_lock lock(mutex_);
        while (!stopping_) {
          redraw();
          tick_.wait_for(lock, std::chrono::seconds(1));
        }
      });
  }
  ~Display() { finish(); }

  void started(const std::string& name) {
    std::lock_guard lock(mutex_);
    running_.insert(name);
    if (terminal_)
      redraw();
    else
      log_->info("{}: started ({} running)", name, running_.size());
  }

  void finished(const std::string& name, const JobOutcome& outcome) {
    std::lock_guard lock(mutex_);
    running_.erase(name);
    ++done_;
    if (outcome.status == JobStatus::Baked) baked_seconds_ += outcome.seconds, ++baked_;
    if (outcome.status == JobStatus::Failed) ++failed_;
    const char* what = outcome.status == JobStatus::Baked     ? "baked"
                       : outcome.status == JobStatus::Skipped ? "complete, skipped (resumed)"
                       : outcome.status == JobStatus::Failed  ? "FAILED"
                                                              : "stopped";
    std::string line = fmt::format("[{}/{}] {}: {} in {:.1f} s", done_, total_, name, what, outcome.seconds);
    if (outcome.status == JobStatus::Failed) line += ": " + outcome.message;
    if (terminal_) {
      // Failures stay on screen; everything else lives in the status line.
      if (outcome.status == JobStatus::Failed) std::fprintf(stderr, "\r\033[K%s\n", line.c_str());
      redraw();
    } else {
      if (outcome.status == JobStatus::Failed)
        log_->error("{}", line);
      else
        log_->info("{} (ETA {})", line, clockText(eta()));
    }
  }

  void finish() {
    {
      std::lock_guard lock(mutex_);
      if (stopping_) return;
      stopping_ = true;
      if (terminal_) std::fprintf(stderr, "\r\033[K"), std::fflush(stderr);
    }
    tick_.notify_all();
    if (ticker_.joinable()) ticker_.join();
  }

 private:
  // Remaining jobs × mean seconds of the jobs baked so far, shared among the parallel jobs.
  double eta() const {
    if (baked_ == 0) return 0;
    const double remaining = double(total_ - done_);
    return remaining * (baked_seconds_ / baked_) / std::max(1.0, std::min<double>(jobs_, remaining));
  }

  void redraw() {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    std::string running;
    for (const auto& name : running_) running += (running.empty() ? "" : ", ") + name;
    const bool stopping = cancel_ && cancel_->load();
    std::string line = fmt::format("{}[{}/{}] {} failed, elapsed {}, ETA {}{}{}",
                                   stopping ? "stopping at the next stage (Ctrl-C again: at once) " : "", done_, total_,
                                   failed_, clockText(elapsed), baked_ ? clockText(eta()) : std::string("--:--"),
                                   running.empty() ? "" : " | ", running);
    if (line.size() > 150) line = line.substr(0, 147) + "...";
    std::fprintf(stderr, "\r\033[K%s", line.c_str());
    std::fflush(stderr);
  }

  std::mutex mutex_;
  std::condition_variable tick_;
  std::thread ticker_;
  bool stopping_ = false;
  const std::size_t total_;
  const int jobs_;
  const bool terminal_;
  const std::atomic<bool>* cancel_;
  const std::shared_ptr<spdlog::logger> log_;
  const Clock::time_point start_ = Clock::now();
  std::set<std::string> running_;
  std::size_t done_ = 0;
  int baked_ = 0, failed_ = 0;
  double baked_seconds_ = 0;
};

LibraryProgress::LibraryProgress(std::size_t total_jobs, int jobs_at_once, bool terminal,
                                 const std::atomic<bool>* cancel)
    : display_(std::make_unique<Display>(total_jobs, jobs_at_once, terminal, cancel)) {}

LibraryProgress::~LibraryProgress() = default;

LibraryObserver LibraryProgress::observer() {
  Display* display = display_.get();
  return {[display](const std::string& job) { display->started(job); },
          [display](const std::string& job, const JobOutcome& outcome) { display->finished(job, outcome); }};
}

void LibraryProgress::finish() {
  display_->finish();
}

}  // namespace rockbake
