// The progress display of `rockbake library`: on a terminal one status line
// redrawn in place (done/total, failures, elapsed, ETA, running jobs) that
// ticks every second; otherwise one log line per job. Fed by the library
// bake's observer callbacks (pipeline/library_bake.h), from any thread.
#pragma once

#include <atomic>
#include <memory>

#include "pipeline/library_bake.h"

namespace rockbake {

class LibraryProgress {
 public:
  LibraryProgress(std::size_t total_jobs, int jobs_at_once, bool terminal, const std::atomic<bool>* cancel);
  ~LibraryProgress();
  LibraryProgress(const LibraryProgress&) = delete;
  LibraryProgress& operator=(const LibraryProgress&) = delete;

  // Callbacks for LibraryBakeOptions::observer; they refer to this display.
  LibraryObserver observer();
  // Clears the status line and stops its ticking (also done on destruction).
  void finish();

 private:
  class Display;
  std::unique_ptr<Display> display_;
};

}  // namespace rockbake
