// Serving a local page until Ctrl-C or SIGTERM (docs/studio.md, docs/review.md): the one
// way the studio's and the review's servers run and stop.
//
// StopSignals, made first, blocks both signals in this thread, so every thread started
// after it (TBB's workers, the server's) inherits the mask and none is interrupted; a
// thread of its own waits for either and calls `on_stop` once. Destroyed, it wakes that
// thread if nothing came, joins it and unblocks the signals.
#pragma once

#include <csignal>
#include <functional>
#include <string>
#include <thread>

#include "http/local_server.h"

namespace rockbake::http {

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

// Where to listen and what the server is called in its messages ("studio", "review").
struct ServeOptions {
  std::string name;
  std::string host = "127.0.0.1";
  int port = 0;      // 0: a free one
  std::string what;  // logged after "<name>: " when serving, e.g. the library's folder
};

// Listens (a failure is a std::runtime_error that says to try another port), prints
// "<name>: <url>" on stdout for whoever started it, and serves until a signal arrives;
// then `on_stop` (cancel the work under way) runs before the server stops. `signals`
// must have been made before any thread that must not see the signals.
void serveUntilStopped(StopSignals& signals, LocalServer& server, const ServeOptions& options,
                       const std::function<void()>& on_stop = {});

}  // namespace rockbake::http
