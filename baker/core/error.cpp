#include "core/error.h"

#include <fmt/format.h>

namespace rockbake {

std::string escapeControlBytes(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f)
      out += fmt::format("\\x{:02x}", byte);
    else
      out += c;
  }
  return out;
}

std::string escapeControlBytesKeepingLines(const std::string& text) {
  std::string out;
  std::size_t start = 0;
  const std::size_t end = !text.empty() && text.back() == '\n' ? text.size() - 1 : text.size();
  while (start <= end) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos || nl > end) nl = end;
    if (start > 0) out += "\n  ";
    out += escapeControlBytes(text.substr(start, nl - start));
    start = nl + 1;
  }
  return out;
}

namespace {

std::string formatMessage(const SourceLocation& where, const std::string& key_path, const std::string& problem,
                          const std::string& hint) {
  std::string message = escapeControlBytes(where.file);
  if (where.line > 0) message += fmt::format(":{}", where.line);
  if (where.line > 0 && where.column > 0) message += fmt::format(":{}", where.column);
  if (!message.empty()) message += ": ";
  if (!key_path.empty()) message += fmt::format("{}: ", escapeControlBytes(key_path));
  message += escapeControlBytes(problem);
  if (!hint.empty()) message += fmt::format(" ({})", hint);
  return message;
}

}  // namespace

InputError::InputError(SourceLocation where, std::string key_path, std::string problem, std::string hint)
    : std::runtime_error(formatMessage(where, key_path, problem, hint)),
      where_(std::move(where)),
      key_path_(std::move(key_path)),
      problem_(std::move(problem)) {}

}  // namespace rockbake
