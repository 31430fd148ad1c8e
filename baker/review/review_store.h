// Verdicts and notes on a library's assets (docs/review.md, "review.json"):
// OUT/review.json, {"rockbake_review": 1, "assets": {NAME: {"status", "note",
// "input_hash", "updated"}}}, with status "approved", "needs-work" or
// "rejected" and the asset's input hash when the verdict was given, so that a
// re-bake with other inputs shows the verdict as stale.
//
// A save merges one asset into the file as it is on disk now, under a lock
// (a mutex between this server's threads, flock on OUT/.review.lock between
// processes), and replaces the file atomically: two browsers, or two servers,
// saving at once both keep their verdicts; a reader never sees half a file.
#pragma once

#include <filesystem>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

namespace rockbake {

inline constexpr const char* kReviewFile = "review.json";

struct Verdict {
  std::string status;      // "approved", "needs-work", "rejected"
  std::string note;        // at most kMaxNoteBytes of UTF-8
  std::string input_hash;  // the asset's when the verdict was given
  std::string updated;     // UTC, ISO 8601
};

inline constexpr std::size_t kMaxNoteBytes = 16 * 1024;

// True for the three verdicts above.
bool isVerdictStatus(const std::string& status);

class ReviewStore {
 public:
  explicit ReviewStore(std::filesystem::path library_dir);

  // The file's "assets" object as it is on disk ({} when there is none yet).
  // Throws std::runtime_error naming the file when it is not a review file.
  nlohmann::json verdicts() const;

  // Merges one asset's verdict into the file and returns what was stored.
  // Throws std::runtime_error naming the file when it cannot be read or written.
  Verdict save(const std::string& asset, const Verdict& verdict);

 private:
  std::filesystem::path dir_;
  mutable std::mutex mutex_;
};

}  // namespace rockbake
