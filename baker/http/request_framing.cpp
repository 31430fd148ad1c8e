#include "http/request_framing.h"

#include <algorithm>
#include <cctype>
#include <optional>

#include <fmt/format.h>

#include "http/header_text.h"

namespace rockbake::http {
namespace {

Framing refused(int status, std::string message) {
  Framing f;
  f.state = Framing::State::Refused;
  f.status = status;
  f.message = std::move(message);
  return f;
}

std::string kib(std::size_t bytes) {
  return bytes % 1024 == 0 ? fmt::format("{} KiB", bytes / 1024) : fmt::format("{} bytes", bytes);
}

std::string mib(std::size_t bytes) {
  return bytes % (1 << 20) == 0 ? fmt::format("{} MiB", bytes >> 20) : kib(bytes);
}

// The header lines (after the request line) of a whole header block.
Framing readHeaders(std::string_view block, const FramingLimits& limits) {
  Framing f;
  f.header_bytes = block.size();
  std::optional<std::size_t> length;
  std::size_t at = block.find("\r\n") + 2;  // past the request line
  while (at < block.size()) {
    const std::size_t end = block.find("\r\n", at);
    const std::string_view line = block.substr(at, end - at);
    at = end + 2;
    if (line.empty()) break;
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) continue;  // not a header; cpp-httplib skips it too
    const std::string_view name = line.substr(0, colon), value = trimmed(line.substr(colon + 1));
    if (sameName(name, "transfer-encoding")) {
      if (!sameName(value, "chunked"))
        return refused(
            501, "Transfer-Encoding '" + std::string(value) + "' is not accepted; send chunked or a Content-Length");
      f.chunked = true;
    }
    if (sameName(name, "expect")) f.expect_continue = sameName(value, "100-continue");
    if (!sameName(name, "content-length")) continue;
    const std::optional<std::size_t> n = decimal(value, 19);
    if (!n || (length && *length != *n))
      return refused(400, "the request's Content-Length is not one whole number of bytes");
    length = n;
  }
  if (f.chunked && length) return refused(400, "the request has both Content-Length and Transfer-Encoding");
  f.content_length = length.value_or(0);
  if (f.content_length > limits.max_body_bytes)
    return refused(413, fmt::format("the request body is {} bytes; the server takes at most {}", f.content_length,
                                    mib(limits.max_body_bytes)));
  return f;
}

// A chunked body (RFC 9112 §7.1) from its start: Complete with its wire length
// once the last chunk and the trailers have arrived.
Framing frameChunks(std::string_view body, const FramingLimits& limits, Framing f) {
  std::size_t at = 0, decoded = 0;
  bool trailers = false;  // after the last chunk: header lines up to an empty one
  for (;;) {
    if (at > maxBodyWireBytes(limits))
      return refused(413, "the request body's chunks are too small (their framing is over " +
                              mib(limits.max_body_bytes) + "); send larger chunks or a Content-Length");
    const std::size_t end = body.find("\r\n", at);
    if (end == std::string_view::npos) return f;  // NeedMore
    const std::string_view line = body.substr(at, end - at);
    at = end + 2;
    if (trailers) {
      if (line.empty()) break;
      continue;
    }
    const std::string_view digits = trimmed(line.substr(0, line.find(';')));
    std::size_t size = 0;
    if (digits.empty() || digits.size() > 8 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); }))
      return refused(400, "the request's chunked body is malformed");
    for (const char c : digits)
      size =
          size * 16 + std::size_t(std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : std::tolower(c) - 'a' + 10);
    if (size == 0) {
      trailers = true;
      continue;
    }
    if ((decoded += size) > limits.max_body_bytes)
      return refused(413, "the request body is over " + mib(limits.max_body_bytes) + ", the most the server takes");
    if (body.size() < at + size + 2) return f;  // NeedMore
    if (body.substr(at + size, 2) != "\r\n") return refused(400, "the request's chunked body is malformed");
    at += size + 2;
  }
  f.content_length = at;
  f.state = Framing::State::Complete;
  return f;
}

}  // namespace

std::size_t maxBodyWireBytes(const FramingLimits& limits) {
  return 2 * limits.max_body_bytes + 4096;
}

Framing frameRequest(std::string_view received, const FramingLimits& limits) {
  const std::size_t search = std::min(received.size(), limits.max_header_bytes);
  const std::size_t end = received.substr(0, search).find("\r\n\r\n");
  const std::string_view block =
      end == std::string_view::npos ? received.substr(0, search) : received.substr(0, end + 4);
  const std::size_t lines = std::size_t(std::count(block.begin(), block.end(), '\n')) - (end == block.npos ? 0 : 1);
  if (lines > limits.max_headers + 1)
    return refused(431, fmt::format("the request has more than {} headers", limits.max_headers));
  if (end == std::string_view::npos) {
    if (received.size() >= limits.max_header_bytes)
      return refused(431, "the request's headers are over " + kib(limits.max_header_bytes));
    return {};
  }
  // Lines end in CRLF and nowhere else. cpp-httplib also ends a line at a bare LF, so a header
  // after one would reach it unseen by this framing and by the layer's own Range handling.
  for (std::size_t i = 0; i < block.size(); ++i) {
    const bool bare_lf = block[i] == '\n' && (i == 0 || block[i - 1] != '\r');
    const bool bare_cr = block[i] == '\r' && (i + 1 == block.size() || block[i + 1] != '\n');
    if (bare_lf || bare_cr) return refused(400, "the request's head has a line break that is not CR LF");
  }
  Framing f = readHeaders(block, limits);
  if (f.state == Framing::State::Refused) return f;
  if (f.chunked) return frameChunks(received.substr(f.header_bytes), limits, f);
  f.state = received.size() >= f.requestBytes() ? Framing::State::Complete : Framing::State::NeedMore;
  return f;
}

}  // namespace rockbake::http
