// LD_PRELOADed into rockbake by tests/pipeline/asset_folder_test.cpp: ends the
// process with SIGKILL just before its N-th change to the filesystem under a
// folder (a rename or a removal), so a test can stop a bake at every point of
// its commit and look at what is left.
//
//   ROCKBAKE_KILL_UNDER=/path   only changes to paths under it count
//   ROCKBAKE_KILL_AT=N          the change to stop before (1 = the first); unset or 0: none
//   ROCKBAKE_KILL_COUNT=FILE    the number of changes counted is written there at exit
//   ROCKBAKE_NO_EXCHANGE=1      renameat2 with flags fails with EINVAL, as on NFS
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

std::atomic<long> changes{0};

const char* env(const char* name) {
  const char* value = std::getenv(name);
  return value && *value ? value : nullptr;
}

// `path` made absolute against `dirfd` (AT_FDCWD: the working folder).
std::string absolute(int dirfd, const char* path) {
  if (!path) return {};
  if (path[0] == '/') return path;
  char base[PATH_MAX] = {};
  if (dirfd == AT_FDCWD) {
    if (!::getcwd(base, sizeof base)) return path;
  } else {
    const std::string link = "/proc/self/fd/" + std::to_string(dirfd);
    if (::readlink(link.c_str(), base, sizeof base - 1) < 0) return path;
  }
  return std::string(base) + "/" + path;
}

bool under(const std::string& path) {
  const char* root = env("ROCKBAKE_KILL_UNDER");
  return root && path.compare(0, std::strlen(root), root) == 0;
}

void writeCount() {
  if (const char* file = env("ROCKBAKE_KILL_COUNT")) {
    if (FILE* out = std::fopen(file, "w")) {
      std::fprintf(out, "%ld\n", changes.load());
      std::fclose(out);
    }
  }
}

// Called before each change: counts it when it touches the folder, and stops the process at the N-th.
void change(int dirfd, const char* path, int dirfd2 = AT_FDCWD, const char* path2 = nullptr) {
  static const bool registered = std::atexit(writeCount) == 0;
  (void)registered;
  if (!under(absolute(dirfd, path)) && !under(absolute(dirfd2, path2))) return;
  const long n = ++changes;
  const char* at = env("ROCKBAKE_KILL_AT");
  if (at && std::atol(at) == n) {
    writeCount();
    ::kill(::getpid(), SIGKILL);
  }
}

template <typename F>
F next(const char* name) {
  return reinterpret_cast<F>(::dlsym(RTLD_NEXT, name));
}

}  // namespace

// Declared noexcept as glibc declares them (__THROW).
extern "C" {

int rename(const char* from, const char* to) noexcept {
  change(AT_FDCWD, from, AT_FDCWD, to);
  return next<int (*)(const char*, const char*)>("rename")(from, to);
}

int renameat(int fromfd, const char* from, int tofd, const char* to) noexcept {
  change(fromfd, from, tofd, to);
  return next<int (*)(int, const char*, int, const char*)>("renameat")(fromfd, from, tofd, to);
}

int renameat2(int fromfd, const char* from, int tofd, const char* to, unsigned flags) noexcept {
  if (flags != 0 && env("ROCKBAKE_NO_EXCHANGE")) {
    errno = EINVAL;
    return -1;
  }
  change(fromfd, from, tofd, to);
  return next<int (*)(int, const char*, int, const char*, unsigned)>("renameat2")(fromfd, from, tofd, to, flags);
}

int unlink(const char* path) noexcept {
  change(AT_FDCWD, path);
  return next<int (*)(const char*)>("unlink")(path);
}

int unlinkat(int dirfd, const char* path, int flags) noexcept {
  change(dirfd, path);
  return next<int (*)(int, const char*, int)>("unlinkat")(dirfd, path, flags);
}

int rmdir(const char* path) noexcept {
  change(AT_FDCWD, path);
  return next<int (*)(const char*)>("rmdir")(path);
}

int remove(const char* path) noexcept {
  change(AT_FDCWD, path);
  return next<int (*)(const char*)>("remove")(path);
}

}  // extern "C"
