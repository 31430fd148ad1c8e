#include "http/serve_until_stopped.h"

#include <pthread.h>

#include <iostream>
#include <stdexcept>

#include <spdlog/spdlog.h>

namespace rockbake::http {

StopSignals::StopSignals() {
  sigemptyset(&signals_);
  sigaddset(&signals_, SIGINT);
  sigaddset(&signals_, SIGTERM);
  sigaddset(&signals_, SIGUSR1);  // our own wake-up, when the server stops for another reason
  pthread_sigmask(SIG_BLOCK, &signals_, nullptr);
}

StopSignals::~StopSignals() {
  if (waiter_.joinable()) {
    pthread_kill(waiter_.native_handle(), SIGUSR1);
    waiter_.join();
  }
  pthread_sigmask(SIG_UNBLOCK, &signals_, nullptr);
}

void StopSignals::whenReceived(std::function<void()> on_stop) {
  waiter_ = std::thread([this, on_stop = std::move(on_stop)] {
    int signal = 0;
    sigwait(&signals_, &signal);
    if (signal != SIGUSR1) on_stop();
  });
}

void serveUntilStopped(StopSignals& signals, LocalServer& server, const ServeOptions& options,
                       const std::function<void()>& on_stop) {
  try {
    server.listen(options.host, options.port);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) +
                             " (in use, or not an address of this machine); try another --port or --port 0");
  }
  signals.whenReceived([&server, on_stop] {
    if (on_stop) on_stop();
    server.stop();
  });
  std::cout << options.name << ": " << server.url() << std::endl;
  spdlog::info("{}: {}; Ctrl-C stops", options.name, options.what);
  server.serve();
  spdlog::info("{}: stopped", options.name);
}

}  // namespace rockbake::http
