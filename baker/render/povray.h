// Running POV-Ray as a subprocess (docs/rendering.md): explicit arguments, the asset
// folder as working directory, a timeout, its messages captured.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockbake {

struct PovrayJob {
  std::filesystem::path working_dir;  // POV-Ray runs here (a user's povray.conf may restrict I/O to it)
  std::filesystem::path scene;        // +I, relative to working_dir or absolute
  std::filesystem::path output;       // +O (an .exr; +FE), relative to working_dir or absolute
  int width = 640;
  int height = 480;
  int quality = 9;         // +Q0..11
  double antialias = 0.3;  // +A<threshold>; <= 0: -A
  int threads = 1;         // +WT<threads>: POV-Ray's render threads (>= 1)
  // +SR/+ER: render only rows [first_row, end_row) (0-based; end_row 0: to the bottom). The
  // file still holds the whole image, the other rows black. With one thread, a band whose
  // rows start and end on kPovrayBlockRows boundaries holds the pixels of the whole render
  // exactly (docs/rendering.md, "Running POV-Ray").
  int first_row = 0;
  int end_row = 0;
  std::chrono::seconds timeout{1800};
  std::string executable = "povray";  // looked up on PATH
  // When set and it turns true, POV-Ray is killed within a second and
  // runPovray throws PovrayError ("cancelled"). POV-Ray runs in a process
  // group of its own, so a terminal's Ctrl-C reaches only the baker, which
  // decides (through this flag) what stops.
  const std::atomic<bool>* cancel = nullptr;
};

struct PovrayResult {
  double seconds = 0;
  std::string messages;  // stdout and stderr together
};

// Thrown when POV-Ray is missing, fails, or times out. what() says which, with
// the tail of POV-Ray's messages (its own parse error, for a broken template).
class PovrayError : public std::runtime_error {
 public:
  explicit PovrayError(const std::string& what) : std::runtime_error(what) {}
};

// POV-Ray's render block, rows and columns (+BS): passed explicitly, since bands of a still
// are cut at block boundaries.
inline constexpr int kPovrayBlockRows = 32;

// The argument vector runPovray passes (argv[0] = executable). Antialiasing
// jitter is always off (-J), so the pixels are the same at any +WT.
std::vector<std::string> povrayArguments(const PovrayJob& job);

// POV-Ray's own transient failure on a loaded machine, retried by runPovray
// (up to 4 attempts) rather than reported.
inline constexpr const char* kWorkerStartupTimeout = "Timed out waiting for worker thread startup";

PovrayResult runPovray(const PovrayJob& job);

}  // namespace rockbake
