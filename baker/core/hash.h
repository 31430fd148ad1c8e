// Counter-based hashing: every random choice is a pure function of
// (seed, purpose, cycle, cell), never of a thread or a call order (docs/model.md §10).
#pragma once

#include <cstdint>
#include <string_view>

namespace rockbake {

// SplitMix64's finaliser: a bijective 64-bit mixer with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// FNV-1a of a purpose name, so purposes read as words at the call site.
constexpr std::uint64_t purposeId(std::string_view purpose) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (char c : purpose) h = (h ^ std::uint8_t(c)) * 0x100000001b3ull;
  return h;
}

constexpr std::uint64_t counterHash(std::uint64_t seed, std::uint64_t purpose, std::uint64_t cycle,
                                    std::uint64_t cell) {
  return mix64(mix64(mix64(mix64(seed) ^ purpose) ^ cycle) ^ cell);
}

// Uniform in [0, 1) from the top 53 bits.
constexpr double unitInterval(std::uint64_t bits) {
  return double(bits >> 11) * 0x1.0p-53;
}

}  // namespace rockbake
