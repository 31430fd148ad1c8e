// SHA-256 fingerprints (OpenSSL) for manifests and resume checks.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace rockbake {

// 64 lower-case hex digits.
std::string sha256Hex(std::string_view bytes);

// The file's bytes, streamed. Throws std::runtime_error naming the file when it
// cannot be read.
std::string sha256File(const std::filesystem::path& file);

}  // namespace rockbake
