// What a local server (http/local_server.h) lets one request, one client and all of
// them together cost, and what it answers past each bound (docs/studio.md, "The
// server's promises"). The connection loop (http/connection_loop.h) enforces them.
#pragma once

#include <chrono>
#include <cstddef>

namespace rockbake::http {

struct Limits {
  std::size_t max_body_bytes = 1 << 20;            // a larger body: 413, and it is not read
  std::size_t max_header_bytes = 16 << 10;         // request line and headers (431)
  std::size_t max_headers = 64;                    // header lines (431)
  std::chrono::milliseconds request_time{10'000};  // from connecting to the request's last byte (408)
  std::chrono::milliseconds answer_time{30'000};   // to send an answer, then the connection is closed
  std::chrono::milliseconds slow_after{250};       // a request still arriving after this long is slow
  std::size_t max_connections_per_client = 16;     // slow requests per client address: its oldest beyond go (408)
  std::size_t max_connections = 256;               // in all: a new one replaces the oldest slow request (408),
                                                   // or is refused (503) when none is slow
  std::size_t max_buffered_bytes = 64 << 20;       // request bodies being read, all together (503)
  std::size_t max_waiting_requests = 64;           // read whole and waiting for a worker (503)
  int workers = 4;                                 // threads running handlers
};

}  // namespace rockbake::http
