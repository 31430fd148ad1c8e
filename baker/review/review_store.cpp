#include "review/review_store.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <stdexcept>

#include "platform/atomic_file.h"
#include "review/library_json.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

std::string utcNow() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// flock on OUT/.review.lock for the lifetime of the object: one writer at a
// time across processes (the file itself is replaced, so it cannot carry the lock).
class FileLock {
 public:
  explicit FileLock(const fs::path& file) {
    // O_NOFOLLOW: a link planted as the lock (dangling or not) would have the
    // save create or lock a file outside OUT; O_NONBLOCK: a FIFO would wait.
    fd_ = open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    struct stat st {};
    if (fd_ >= 0 && (fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode))) {
      close(fd_);
      fd_ = -1;
      errno = EINVAL;
    }
    if (fd_ < 0)
      throw std::runtime_error("cannot open " + file.string() + " as a lock file (" +
                               (errno == ELOOP || errno == EINVAL ? std::string("it is a link or not a regular file")
                                                                  : std::string(std::strerror(errno))) +
                               "); remove it and save again");
    while (flock(fd_, LOCK_EX) != 0)
      if (errno != EINTR) {
        const int e = errno;
        close(fd_);
        throw std::runtime_error("cannot lock " + file.string() + ": " + std::strerror(e));
      }
  }
  ~FileLock() { close(fd_); }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_ = -1;
};

nlohmann::json readReviewFile(const fs::path& dir) {
  const fs::path file = dir / kReviewFile;
  const LibraryJson read = readLibraryJson(dir, kReviewFile, kMaxLibraryJsonBytes);
  if (!read.present) return {{"rockbake_review", 1}, {"assets", nlohmann::json::object()}};
  const nlohmann::json& j = read.value;
  if (!read.problem.empty() && !read.not_json)
    throw std::runtime_error(read.problem + "; move it away and review again");
  if (read.not_json || !j.is_object() || !j.contains("assets") || !j["assets"].is_object())
    throw std::runtime_error(file.string() +
                             " is not a review file ({\"rockbake_review\": 1, \"assets\": {...}}); move it "
                             "away and review again");
  return j;
}

}  // namespace

bool isVerdictStatus(const std::string& status) {
  return status == "approved" || status == "needs-work" || status == "rejected";
}

ReviewStore::ReviewStore(fs::path library_dir) : dir_(std::move(library_dir)) {}

nlohmann::json ReviewStore::verdicts() const {
  return readReviewFile(dir_)["assets"];
}

Verdict ReviewStore::save(const std::string& asset, const Verdict& verdict) {
  const std::lock_guard<std::mutex> guard(mutex_);
  const FileLock lock(dir_ / ".review.lock");
  nlohmann::json file = readReviewFile(dir_);
  Verdict stored = verdict;
  stored.updated = utcNow();
  file["rockbake_review"] = 1;
  file["assets"][asset] = {
      {"status", stored.status}, {"note", stored.note}, {"input_hash", stored.input_hash}, {"updated", stored.updated}};
  writeFileAtomically(dir_ / kReviewFile, file.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  return stored;
}

}  // namespace rockbake
