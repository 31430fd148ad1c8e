// Range requests (RFC 9110 §14), answered by the layer itself for every GET
// route whose answer is a 200 (docs/studio.md, "The server's promises"). A
// Range header that is not `bytes=…`, or is malformed, is ignored (the whole
// answer, 200); ranges that overlap or touch are coalesced, so no byte is sent
// twice; more than kMaxByteRanges after that, or more than kMaxRangeSpecs as
// written, are ignored too. One range is a 206 with `Content-Range: bytes
// FIRST-LAST/SIZE`, several a multipart/byteranges 206, none that the answer
// has a 416 with `Content-Range: bytes */SIZE`.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "http/route.h"

namespace rockbake::http {

inline constexpr std::size_t kMaxRangeSpecs = 64;  // as written in the header
inline constexpr std::size_t kMaxByteRanges = 8;   // after coalescing

struct ByteRange {
  std::uint64_t first = 0, last = 0;  // inclusive, first <= last < size
};

// The ranges `header` asks of `size` bytes, sorted and coalesced; empty when
// none of them is satisfiable; nothing when the header is to be ignored.
std::optional<std::vector<ByteRange>> byteRanges(const std::string& header, std::uint64_t size);

// Turns a 200 `response` into the answer to `header` (see above).
void answerRanges(Response& response, const std::string& header);

}  // namespace rockbake::http
