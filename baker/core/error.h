// Errors the command line turns into exit statuses (docs/command-line.md):
//   InputError → 2 (bad preset or arguments), anything else → 1.
#pragma once

#include <stdexcept>
#include <string>

namespace rockbake {

// Where in an input a problem is. line/column are 1-based; 0 = unknown.
struct SourceLocation {
  std::string file;  // path as given, or "--set" / "<command line>"
  int line = 0;
  int column = 0;
};

// `text` with every control byte (and DEL) written as \xNN: what an input holds
// may end up in a message, and must not reach the terminal raw.
std::string escapeControlBytes(const std::string& text);

// The same, but a message of several lines (a helper program's own words) stays several
// lines: each line feed is kept and the next line indented by two spaces, so no line of it
// can pass for a log line of ours. A trailing line feed is dropped.
std::string escapeControlBytesKeepingLines(const std::string& text);

// A problem with what the user gave us: a preset, a file it names, a flag.
// what() is the full message: "file:line:col: key.path: problem. hint", with
// control bytes in the file, key path and problem escaped.
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, std::string key_path, std::string problem, std::string hint = {});

  const SourceLocation& where() const { return where_; }
  const std::string& keyPath() const { return key_path_; }
  const std::string& problem() const { return problem_; }

 private:
  SourceLocation where_;
  std::string key_path_;
  std::string problem_;
};

}  // namespace rockbake
