#include "review/review_store.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/atomic_file.h"

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
    fd_ = open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error("cannot open " + file.string() + ": " + std::strerror(errno));
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

nlohmann::json readReviewFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return {{"rockbake_review", 1}, {"assets", nlohmann::json::object()}};
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("assets") || !j["assets"].is_object())
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
  return readReviewFile(dir_ / kReviewFile)["assets"];
}

Verdict ReviewStore::save(const std::string& asset, const Verdict& verdict) {
  const std::lock_guard<std::mutex> guard(mutex_);
  const FileLock lock(dir_ / ".review.lock");
  nlohmann::json file = readReviewFile(dir_ / kReviewFile);
  Verdict stored = verdict;
  stored.updated = utcNow();
  file["rockbake_review"] = 1;
  file["assets"][asset] = {
      {"status", stored.status}, {"note", stored.note}, {"input_hash", stored.input_hash}, {"updated", stored.updated}};
  writeFileAtomically(dir_ / kReviewFile, file.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  return stored;
}

}  // namespace rockbake
