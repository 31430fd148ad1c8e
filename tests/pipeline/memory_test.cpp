// What this process may use (platform/memory.h), against what /proc and its limits say.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <fstream>
#include <string>

#include "platform/memory.h"

namespace rockbake {
namespace {

std::uint64_t vmSizeBytes() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmSize:", 0) == 0) return std::stoull(line.substr(7)) * 1024;
  return 0;
}

TEST(Memory, AnAddressSpaceLimitBoundsTheLimitAndTheHeadroom) {
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_AS, &old), 0);
  const std::uint64_t unlimited_headroom = memoryHeadroomBytes();
  EXPECT_GT(unlimited_headroom, std::uint64_t(0));
  EXPECT_GT(memoryLimitBytes(), std::uint64_t(64) << 20);

  // 48 MiB above this process's size now: the headroom is about that, and the limit is it.
  struct rlimit tight = old;
  tight.rlim_cur = vmSizeBytes() + (std::uint64_t(48) << 20);
  ASSERT_EQ(::setrlimit(RLIMIT_AS, &tight), 0);
  const std::uint64_t headroom = memoryHeadroomBytes(), limit = memoryLimitBytes();
  ASSERT_EQ(::setrlimit(RLIMIT_AS, &old), 0);
  EXPECT_GT(headroom, std::uint64_t(40) << 20);
  EXPECT_LE(headroom, std::uint64_t(48) << 20);
  EXPECT_EQ(limit, tight.rlim_cur);
}

}  // namespace
}  // namespace rockbake
