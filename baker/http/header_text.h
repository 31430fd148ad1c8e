// The small pieces of reading an HTTP head that the request framing and the byte ranges share
// (RFC 9110 §5: field names are case-insensitive, values are trimmed of spaces and tabs).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace rockbake::http {

// `s` without leading and trailing spaces and tabs.
std::string_view trimmed(std::string_view s);

// Whether two field names (or tokens) are equal ignoring ASCII case.
bool sameName(std::string_view a, std::string_view b);

// `s` as a whole decimal number: 1 to `max_digits` digits (at most 19: no overflow), no sign or
// space inside; nothing otherwise.
std::optional<std::uint64_t> decimal(std::string_view s, std::size_t max_digits);

}  // namespace rockbake::http
