// The studio's play button (docs/studio.md, "Transport"): a thread that runs a
// cycle at a time while playing, taking the studio's lock for each cycle and
// letting requests in between, at a set rate or as fast as cycles run; it stops
// at the preset's end. A cycle that fails (out of memory) pauses it, and the
// message stays for the page (lastProblem) until the next play.
#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "studio/studio_session.h"

namespace rockbake {

class SimulationLoop {
 public:
  // `mutex` guards `session`: the loop holds it while a cycle runs.
  SimulationLoop(StudioSession& session, std::mutex& mutex);
  ~SimulationLoop();  // stops and joins
  SimulationLoop(const SimulationLoop&) = delete;
  SimulationLoop& operator=(const SimulationLoop&) = delete;

  // Call these holding the mutex.
  void play(double cycles_per_second);  // 0: as fast as cycles run
  void pause();
  bool playing() const { return playing_; }
  double rate() const { return rate_; }
  const std::string& lastProblem() const { return problem_; }

 private:
  void run();

  StudioSession& session_;
  std::mutex& mutex_;
  std::condition_variable wake_;
  std::atomic<bool> playing_{false}, stopping_{false};
  std::atomic<double> rate_{0.0};
  std::string problem_;  // guarded by mutex_
  std::thread thread_;
};

}  // namespace rockbake
