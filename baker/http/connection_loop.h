// The sockets of a local server (http/local_server.h). One thread polls every
// connection without blocking on any: it accepts, reads each request whole
// (framed by http/request_framing.h, within Limits::request_time), and sends
// each answer (within Limits::answer_time). Only a complete request reaches a
// worker thread, which turns its bytes into the answer's; a slow or stuck
// client therefore holds a buffer and a deadline, never a worker.
//   - Refusals before a worker (431, 413, 411, 400, 408, 503) are written by
//     this thread; after a refused body the connection is drained for a moment
//     so the client reads the answer instead of a reset.
//   - A request still arriving after Limits::slow_after is slow. A client
//     address keeps at most max_connections_per_client slow requests: its
//     oldest beyond that are dropped (408) as soon as they turn slow, so a
//     burst of requests that arrive whole at once is never cut short. At
//     max_connections, a new connection takes the place of the oldest slow
//     request of any client (408); when there is none, it is refused (503).
//   - One request per connection: the answer is the last thing sent.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "http/limits.h"

namespace rockbake::http {

// One request as read whole, and who sent it: views of the connection's own
// strings, valid while the answerer runs.
struct RawRequest {
  std::string_view bytes;  // request line, headers and body
  std::string_view peer_address;
  int peer_port = 0;
  std::string_view local_address;
  int local_port = 0;
};

// The answer's bytes (status line, headers, body) for a request. Must not throw.
using Answerer = std::function<std::string(const RawRequest&)>;

// A complete answer {"error": message} with Connection: close, as this layer writes its refusals.
std::string plainAnswer(int status, const std::string& message);

class ConnectionLoop {
 public:
  // Takes the listening socket (non-blocking), and closes it when done.
  ConnectionLoop(int listener, const Limits& limits, Answerer answer);
  ~ConnectionLoop();
  ConnectionLoop(const ConnectionLoop&) = delete;
  ConnectionLoop& operator=(const ConnectionLoop&) = delete;

  void run();   // until stop(); joins its workers before it returns
  void stop();  // from any thread

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbake::http
