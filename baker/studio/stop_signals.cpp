#include "studio/stop_signals.h"

#include <pthread.h>

namespace rockbake {

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

}  // namespace rockbake
