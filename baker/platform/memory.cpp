#include "platform/memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <string>

namespace rockbake {
namespace {

// A "Key:  N kB" line of a /proc file, in bytes; not there: max.
std::uint64_t procKibibytes(const char* file, const std::string& key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + ":", 0) == 0) return std::stoull(line.substr(key.size() + 1)) * 1024;
  return std::numeric_limits<std::uint64_t>::max();
}

}  // namespace

std::uint64_t memoryLimitBytes() {
  std::uint64_t bytes = std::uint64_t(::sysconf(_SC_PHYS_PAGES)) * std::uint64_t(::sysconf(_SC_PAGESIZE));
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    bytes = std::min<std::uint64_t>(bytes, limit.rlim_cur);
  return bytes;
}

std::uint64_t memoryHeadroomBytes() {
  std::uint64_t headroom = procKibibytes("/proc/meminfo", "MemAvailable");
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const std::uint64_t size = procKibibytes("/proc/self/status", "VmSize");
    headroom = std::min<std::uint64_t>(headroom, size < limit.rlim_cur ? limit.rlim_cur - size : 0);
  }
  return headroom;
}

void returnLargeBlocksToTheSystem() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
}

}  // namespace rockbake
