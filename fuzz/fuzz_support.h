// Shared by the libFuzzer targets: a scratch folder per process (on tmpfs when
// there is one, since most readers take a path) and the rule every target
// checks: a reader may refuse an input only with the exceptions its header
// promises. Anything else (another exception, a crash, a sanitizer report, a
// huge allocation) is a finding.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <typeinfo>

namespace rockbake::fuzz {

inline std::filesystem::path scratchDir(const std::string& target) {
  const std::filesystem::path root = std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm")
                                                                               : std::filesystem::temp_directory_path();
  const auto dir = root / ("rockbake-fuzz-" + target + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

inline void writeFile(const std::filesystem::path& file, std::string_view bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

inline std::string readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

// Runs `read`; an exception of type Allowed (or derived) is a refusal, fine; any other is a finding.
template <typename Allowed, typename Read>
bool refusesOnlyWith(Read&& read) {
  try {
    read();
    return true;
  } catch (const Allowed&) {
    return false;
  } catch (const std::exception& e) {
    finding(std::string("unexpected ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    finding("unexpected non-standard exception");
  }
}

}  // namespace rockbake::fuzz
