// The turntable movie (docs/rendering.md, "Turntable movie"): the turntable's
// EXR frames through the OCIO display transform (exrToDisplay, the look of
// render.png), one video frame per view, encoded by FFmpeg's libx264 as H.264
// High profile, yuv420p, BT.709, in an MP4 with its index first (faststart).
//
// FFmpeg runs as its own process (`ffmpeg` on PATH), as POV-Ray does: Debian's
// libavcodec is built with --enable-gpl (avcodec_license() says "GPL version 2
// or later", and libx264 is GPL), and rockbake links nothing GPL. The frames go
// to its standard input as raw RGB, so nothing but the movie is written.
//
// The bytes depend only on the frames and the rate: x264 runs on one thread,
// the muxer writes no time stamp, encoder string or other metadata.
#pragma once

#include <array>
#include <atomic>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "platform/colour.h"

namespace rockbake {

// FFmpeg is killed when it takes no frame, or does not exit once it has them
// all, for this long (docs/rendering.md, "Helper programs").
inline constexpr int kFfmpegStallSeconds = 30;

struct TurntableMovieJob {
  std::vector<std::filesystem::path> frames;  // EXRs of one size, in order
  std::filesystem::path target;               // turntable.mp4; written atomically
  int fps = 24;                               // 1 … 120
  std::filesystem::path ocio_config = defaultOcioConfig();
  std::string executable = "ffmpeg";          // looked up on PATH
  const std::atomic<bool>* cancel = nullptr;  // set: FFmpeg is killed within 0.1 s, MovieError("cancelled")
};

// FFmpeg missing (the message names the Debian package), failing (with the tail
// of its messages), stalled, cancelled, or exiting 0 without writing an MP4
// (no `ftyp` box first); or a frame unreadable. Nothing is left at `target` or
// beside it, and no FFmpeg process: its process group is killed, and it dies
// with the baker (PR_SET_PDEATHSIG).
class MovieError : public std::runtime_error {
 public:
  explicit MovieError(const std::string& what) : std::runtime_error(what) {}
};

// The size the movie has for frames of `width` × `height`: each rounded up to
// an even number (H.264's 4:2:0 needs it); the added column or row repeats the
// last one.
std::array<int, 2> movieFrameSize(int width, int height);

// The argument vector writeTurntableMovie runs (argv[0] = executable).
std::vector<std::string> ffmpegArguments(const TurntableMovieJob& job, int width, int height,
                                         const std::filesystem::path& output);

void writeTurntableMovie(const TurntableMovieJob& job);

}  // namespace rockbake
