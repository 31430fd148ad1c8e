#include "http/byte_ranges.h"

#include <algorithm>
#include <cctype>
#include <random>

#include <fmt/format.h>

#include "http/header_text.h"
#include "http/json_body.h"

namespace rockbake::http {

// Positions of at most 18 digits: sums of two stay far from overflow.
constexpr std::size_t kMostDigits = 18;

std::optional<std::vector<ByteRange>> byteRanges(const std::string& header, std::uint64_t size) {
  std::string_view rest = trimmed(header);
  const std::size_t eq = rest.find('=');
  if (eq == std::string_view::npos) return std::nullopt;
  std::string unit(trimmed(rest.substr(0, eq)));
  std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (unit != "bytes") return std::nullopt;  // an unknown unit is ignored (RFC 9110 §14.2)
  rest.remove_prefix(eq + 1);
  std::vector<ByteRange> ranges;
  std::size_t specs = 0;
  for (;;) {
    const std::size_t comma = rest.find(',');
    const std::string_view spec = trimmed(rest.substr(0, comma));
    if (!spec.empty()) {  // empty list elements are allowed (RFC 9110 §5.6.1)
      if (++specs > kMaxRangeSpecs) return std::nullopt;
      const std::size_t dash = spec.find('-');
      if (dash == std::string_view::npos) return std::nullopt;
      const std::string_view a = spec.substr(0, dash), b = spec.substr(dash + 1);
      if (a.empty()) {  // suffix: the last N bytes
        const auto n = decimal(b, kMostDigits);
        if (!n) return std::nullopt;
        if (*n > 0 && size > 0) ranges.push_back({size - std::min(*n, size), size - 1});
      } else {
        const auto first = decimal(a, kMostDigits);
        const auto last = b.empty() ? std::optional<std::uint64_t>(UINT64_MAX) : decimal(b, kMostDigits);
        if (!first || !last || *last < *first) return std::nullopt;
        if (*first < size) ranges.push_back({*first, std::min(*last, size - 1)});
      }
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  if (specs == 0) return std::nullopt;
  std::sort(ranges.begin(), ranges.end(), [](const ByteRange& x, const ByteRange& y) { return x.first < y.first; });
  std::vector<ByteRange> merged;
  for (const ByteRange& r : ranges)
    if (!merged.empty() && r.first <= merged.back().last + 1)
      merged.back().last = std::max(merged.back().last, r.last);
    else
      merged.push_back(r);
  return merged;
}

void answerRanges(Response& response, const std::string& header) {
  const std::uint64_t size = response.body.size();
  const auto ranges = byteRanges(header, size);
  if (!ranges || ranges->size() > kMaxByteRanges) return;  // the whole answer
  if (ranges->empty()) {
    Response refused =
        errorResponse(416, fmt::format("the Range header ({}) asks for no byte of the {} there are; ask for "
                                       "bytes=0-{} or less",
                                       header.substr(0, 200), size, size ? size - 1 : 0));
    refused.headers.emplace_back("Content-Range", fmt::format("bytes */{}", size));
    response = std::move(refused);
    return;
  }
  response.status = 206;
  if (ranges->size() == 1) {
    const ByteRange r = ranges->front();
    response.headers.emplace_back("Content-Range", fmt::format("bytes {}-{}/{}", r.first, r.last, size));
    response.body = response.body.substr(r.first, r.last - r.first + 1);
    return;
  }
  // Random, so that a file's own bytes are unlikely to hold it.
  std::random_device random;
  const std::string boundary = fmt::format("rockbake-{:08x}{:08x}", random(), random());
  std::string body;
  for (const ByteRange& r : *ranges) {
    body += fmt::format("--{}\r\nContent-Type: {}\r\nContent-Range: bytes {}-{}/{}\r\n\r\n", boundary,
                        response.content_type, r.first, r.last, size);
    body.append(response.body, r.first, r.last - r.first + 1);
    body += "\r\n";
  }
  body += "--" + boundary + "--\r\n";
  response.body = std::move(body);
  response.content_type = "multipart/byteranges; boundary=" + boundary;
}

}  // namespace rockbake::http
