#include "core/error.h"

#include <fmt/format.h>

namespace rockbake {
namespace {

std::string formatMessage(const SourceLocation& where, const std::string& key_path, const std::string& problem,
                          const std::string& hint) {
  std::string message = where.file;
  if (where.line > 0) message += fmt::format(":{}", where.line);
  if (where.line > 0 && where.column > 0) message += fmt::format(":{}", where.column);
  if (!message.empty()) message += ": ";
  if (!key_path.empty()) message += fmt::format("{}: ", key_path);
  message += problem;
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
