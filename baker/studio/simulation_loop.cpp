#include "studio/simulation_loop.h"

#include <chrono>
#include <exception>

#include <spdlog/spdlog.h>

namespace rockbake {

SimulationLoop::SimulationLoop(StudioSession& session, std::mutex& mutex)
    : session_(session), mutex_(mutex), thread_([this] { run(); }) {}

SimulationLoop::~SimulationLoop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void SimulationLoop::play(double cycles_per_second) {
  rate_ = cycles_per_second;
  playing_ = true;
  problem_.clear();
  wake_.notify_all();
}

void SimulationLoop::pause() {
  playing_ = false;
}

void SimulationLoop::run() {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    if (!playing_) {
      wake_.wait(lock, [&] { return stopping_ || playing_; });
      continue;
    }
    const auto started = std::chrono::steady_clock::now();
    try {
      if (session_.atEnd()) {
        playing_ = false;
        continue;
      }
      session_.step();
    } catch (const std::exception& e) {
      playing_ = false;
      try {
        problem_ = e.what();
        spdlog::error("studio: the simulation stopped: {}", e.what());
      } catch (const std::bad_alloc&) {
        problem_.clear();  // no memory even for the message: the page sees the pause
      }
    }
    // Let a waiting request in between cycles; at a set rate, wait out the rest of the cycle's time.
    const double r = rate_;
    const auto due = r > 0 ? started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                           std::chrono::duration<double>(1.0 / r))
                           : std::chrono::steady_clock::now() + std::chrono::milliseconds(1);
    wake_.wait_until(lock, due, [&] { return stopping_.load(); });
  }
}

}  // namespace rockbake
