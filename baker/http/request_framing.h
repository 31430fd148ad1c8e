// Where an HTTP/1.1 request ends, judged from the bytes received so far
// (RFC 9112 §2.1, §6.3), so that a local server reads each request whole before
// any worker sees it, and refuses one that is too large before buffering it:
//   - the request line and headers end at the first empty line (CRLF CRLF);
//     together they are at most `max_header_bytes`, with at most
//     `max_headers` header lines (431 otherwise);
//   - the body is Content-Length bytes, or chunks up to the last, empty one
//     (Transfer-Encoding: chunked, as Node's http client sends a body of no
//     stated length), at most `max_body_bytes` either way (413); chunks spend at
//     most as many bytes again on their framing (413 beyond). Another transfer
//     coding is refused (501), as is a malformed or contradicting length (400).
// Pure: no I/O, no state; the caller passes every byte received since the
// request began, each time more arrive.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rockbake::http {

struct FramingLimits {
  std::size_t max_header_bytes = 16 << 10;  // request line and headers, CRLFs included
  std::size_t max_headers = 64;             // header lines, the request line aside
  std::size_t max_body_bytes = 1 << 20;
};

struct Framing {
  enum class State { NeedMore, Complete, Refused };
  State state = State::NeedMore;
  // Known once the headers are whole:
  std::size_t header_bytes = 0;    // up to and including the empty line
  std::size_t content_length = 0;  // body bytes that follow them (chunked: once Complete, on the wire)
  bool chunked = false;            // Transfer-Encoding: chunked
  bool expect_continue = false;    // Expect: 100-continue
  // When refused: the status and a message that says what to do.
  int status = 0;
  std::string message;

  std::size_t requestBytes() const { return header_bytes + content_length; }
};

// The most bytes a body may take on the wire: its length, or a chunked body's limit with its framing.
std::size_t maxBodyWireBytes(const FramingLimits& limits);

Framing frameRequest(std::string_view received, const FramingLimits& limits);

}  // namespace rockbake::http
