// Ctrl-C and SIGTERM for a server that must stop cleanly (docs/studio.md):
// made first, it blocks both in this thread, so every thread started after it
// (TBB's workers, the server's) inherits the mask and none is interrupted; a
// thread of its own waits for either and calls `on_stop` once. Destroyed, it
// wakes that thread if nothing came, joins it and unblocks the signals.
#pragma once

#include <csignal>
#include <functional>
#include <thread>

namespace rockbake {

class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  // Starts waiting; `on_stop` runs on the waiting thread.
  void whenReceived(std::function<void()> on_stop);

 private:
  sigset_t signals_{};
  std::thread waiter_;
};

}  // namespace rockbake
