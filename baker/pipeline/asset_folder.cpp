#include "pipeline/asset_folder.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <system_error>
#include <vector>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "pipeline/manifest.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

constexpr const char* kForeignHint =
    "rockbake replaces only the asset folders it wrote: move it away, bake into another folder (-o OUT), or give the "
    "asset another name";

fs::path parentOf(const fs::path& asset_dir) {
  return asset_dir.parent_path().empty() ? fs::path(".") : asset_dir.parent_path();
}

// ".<name><suffix>", appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) about
// "." + std::string.
std::string hiddenName(const fs::path& asset_dir, const std::string& suffix) {
  std::string name = ".";
  name += asset_dir.filename().string();
  name += suffix;
  return name;
}

// OUT/.<name>.<what>-<pid>: the hidden folders a bake of OUT/<name> uses beside it.
fs::path hidden(const fs::path& asset_dir, const char* what) {
  return asset_dir.parent_path() / hiddenName(asset_dir, fmt::format(".{}-{}", what, ::getpid()));
}

fs::path lockFile(const fs::path& asset_dir) {
  return asset_dir.parent_path() / hiddenName(asset_dir, ".lock");
}

// The hidden folders of earlier bakes of this asset: .<name>.baking-<pid> (a staging folder; holding
// manifest.json once the bake finished) and .<name>.replaced-<pid> (a previous asset renamed aside).
struct Leftovers {
  std::vector<fs::path> baking, replaced;
};

Leftovers leftoversOf(const fs::path& asset_dir) {
  Leftovers found;
  const std::string prefix = hiddenName(asset_dir, ".");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parentOf(asset_dir), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    for (auto [kind, list] : {std::pair{"baking-", &found.baking}, std::pair{"replaced-", &found.replaced}}) {
      const std::size_t n = std::strlen(kind);
      if (rest.size() > n && rest.compare(0, n, kind) == 0 &&
          rest.find_first_not_of("0123456789", n) == std::string::npos)
        list->push_back(asset_dir.parent_path() / name);
    }
  }
  return found;
}

bool holdsFile(const fs::path& dir, const char* name) {
  std::error_code ec;
  return fs::is_regular_file(fs::symlink_status(dir / name, ec));
}

// A previous asset's folder, once out of place: its manifest goes first, so that a removal cut short
// never leaves a folder that reads as a finished asset.
void discard(const fs::path& dir) {
  std::error_code ignored;
  fs::remove(dir / kManifestFile, ignored);
  fs::remove(dir / kFailureFile, ignored);
  fs::remove_all(dir, ignored);
}

// 0, or the errno of renameat2(from, to, flags).
int renameWith(const fs::path& from, const fs::path& to, unsigned flags) {
  return ::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), flags) == 0 ? 0 : errno;
}

// A commit cut short between its two renames, OUT/<name> missing: the finished bake goes into place, or
// else the previous asset goes back. Which one, or nothing.
std::optional<fs::path> finishCommit(const fs::path& asset_dir, const Leftovers& left) {
  for (const auto* list : {&left.baking, &left.replaced})
    for (const auto& dir : *list)
      if ((holdsFile(dir, kManifestFile) || holdsFile(dir, kFailureFile)) && renameWith(dir, asset_dir, 0) == 0)
        return dir;
  return std::nullopt;
}

bool unsupported(int error) {
  return error == EINVAL || error == ENOSYS || error == EOPNOTSUPP;
}

[[noreturn]] void failRename(int error, const fs::path& from, const fs::path& to) {
  throw fs::filesystem_error("cannot put the finished asset in place", from, to,
                             std::error_code(error, std::generic_category()));
}

// A write lock on the whole file, as an open file description lock (each job of a library its own, even
// within one process); a kernel without them gets a process lock. False when another holds it.
bool tryLock(int fd, const fs::path& file) {
  struct flock lock {};
  lock.l_type = F_WRLCK;
  lock.l_whence = SEEK_SET;
  if (::fcntl(fd, F_OFD_SETLK, &lock) == 0) return true;
  if (errno == EINVAL && ::fcntl(fd, F_SETLK, &lock) == 0) return true;
  if (errno == EACCES || errno == EAGAIN) return false;
  throw std::system_error(errno, std::generic_category(), "cannot lock " + file.string());
}

// Whether another open file description holds a lock on the file.
bool heldElsewhere(int fd) {
  struct flock lock {};
  lock.l_type = F_WRLCK;
  lock.l_whence = SEEK_SET;
  if (::fcntl(fd, F_OFD_GETLK, &lock) != 0 && !(errno == EINVAL && ::fcntl(fd, F_GETLK, &lock) == 0)) return false;
  return lock.l_type != F_UNLCK;
}

// What the lock file says of its holder, one line, escaped.
std::string holderOf(int fd) {
  char text[256] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string said = n > 0 ? std::string(text, std::size_t(n)) : std::string();
  while (!said.empty() && (said.back() == '\n' || said.back() == '\r')) said.pop_back();
  return said.empty() ? "another rockbake process (it has not said which yet)" : escapeControlBytes(said);
}

bool sameFile(int fd, const fs::path& file) {
  struct stat open_file {};
  struct stat named {};
  return ::fstat(fd, &open_file) == 0 && ::stat(file.c_str(), &named) == 0 && open_file.st_ino == named.st_ino &&
         open_file.st_dev == named.st_dev;
}

std::string lockText() {
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return fmt::format("pid {} on host {}, since {:%Y-%m-%dT%H:%M:%SZ}\n", ::getpid(), hostName(), fmt::gmtime(now));
}

[[noreturn]] void refuseHeld(const fs::path& asset_dir, const std::string& holder) {
  throw InputError({asset_dir.string()}, "", "is being written by " + holder,
                   "wait for that bake to finish, or bake into another folder (-o OUT)");
}

}  // namespace

void checkOutFolder(const fs::path& out_dir) {
  for (fs::path p = out_dir; !p.empty(); p = p.parent_path()) {
    std::error_code ec;
    const fs::file_status status = fs::status(p, ec);
    if (fs::is_directory(status)) return;
    if (fs::exists(status))
      throw InputError({out_dir.string()}, "",
                       p == out_dir ? "is a file, not a folder" : p.string() + " is a file, not a folder",
                       "give -o a folder to write the assets in (it is created when missing)");
    if (p == p.parent_path()) return;
  }
}

std::optional<std::string> foreignAssetProblem(const fs::path& asset_dir) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(asset_dir, ec);
  if (!fs::exists(status)) return std::nullopt;
  if (fs::is_symlink(status)) return "is a symbolic link, not an asset folder rockbake wrote";
  if (!fs::is_directory(status)) return "is a file, not an asset folder rockbake wrote";
  if (holdsFile(asset_dir, kManifestFile) || holdsFile(asset_dir, kFailureFile)) return std::nullopt;
  if (fs::is_empty(asset_dir, ec) && !ec) return std::nullopt;  // nothing in it to lose
  return std::string("is a folder rockbake did not write (it holds no ") + kManifestFile + " or " + kFailureFile + ")";
}

std::optional<std::string> assetLockHolder(const fs::path& asset_dir) {
  const int fd = ::open(lockFile(asset_dir).c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return std::nullopt;
  std::optional<std::string> holder;
  if (heldElsewhere(fd)) holder = holderOf(fd);
  ::close(fd);
  return holder;
}

void checkAssetWritable(const fs::path& asset_dir) {
  checkOutFolder(parentOf(asset_dir));
  if (const auto problem = foreignAssetProblem(asset_dir))
    throw InputError({asset_dir.string()}, "", *problem, kForeignHint);
  if (const auto holder = assetLockHolder(asset_dir)) refuseHeld(asset_dir, *holder);
}

AssetLock::AssetLock(const fs::path& asset_dir) : asset_dir_(asset_dir), file_(lockFile(asset_dir)) {
  const fs::path out = parentOf(asset_dir);
  checkOutFolder(out);
  created_out_ = !fs::exists(out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw std::runtime_error("cannot create the output folder " + out.string() + ": " + ec.message());
  // The lock is taken on the file the name holds once it is locked: a holder that just removed it (its
  // bake done) leaves the next one to lock a new file.
  for (;;) {
    fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) {
      const int error = errno;
      if (created_out_) fs::remove(out, ec);
      throw std::runtime_error("cannot create the lock file " + file_.string() + ": " + std::strerror(error));
    }
    if (!tryLock(fd_, file_)) {
      const std::string holder = holderOf(fd_);
      ::close(fd_);
      refuseHeld(asset_dir, holder);
    }
    if (sameFile(fd_, file_)) break;
    ::close(fd_);
  }
  const std::string text = lockText();
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, text.data(), text.size(), 0) != ssize_t(text.size()))
    spdlog::debug("{}: cannot say who holds it: {}", file_.string(), std::strerror(errno));
  on_abnormal_exit_ = std::make_unique<OnAbnormalExit>(file_, "", created_out_);
}

AssetLock::~AssetLock() {
  on_abnormal_exit_.reset();
  if (sameFile(fd_, file_)) ::unlink(file_.c_str());
  ::close(fd_);
  std::error_code ignored;
  if (created_out_) fs::remove(parentOf(asset_dir_), ignored);  // only if left empty
}

void tidyAssetFolder(const AssetLock& lock) {
  const fs::path& asset_dir = lock.assetDir();
  const Leftovers left = leftoversOf(asset_dir);
  std::error_code ec;
  const std::optional<fs::path> placed =
      fs::exists(fs::symlink_status(asset_dir, ec)) ? std::nullopt : finishCommit(asset_dir, left);
  if (placed)
    spdlog::info("{}: put in place from {}, where an interrupted bake left it", asset_dir.string(),
                 placed->filename().string());
  for (const auto* list : {&left.baking, &left.replaced})
    for (const auto& dir : *list)
      if (dir != placed) discard(dir);
}

StagingFolder::StagingFolder(const fs::path& asset_dir, const std::string& out_of_memory, const AssetLock* lock)
    : final_(asset_dir), staging_(hidden(asset_dir, "baking")) {
  if (!lock) own_lock_ = std::make_unique<AssetLock>(asset_dir), lock = own_lock_.get();
  tidyAssetFolder(*lock);
  if (const auto problem = foreignAssetProblem(asset_dir))
    throw InputError({asset_dir.string()}, "", *problem, kForeignHint);
  const bool created_out = own_lock_ && own_lock_->createdOut();
  on_abnormal_exit_ = std::make_unique<OnAbnormalExit>(staging_, out_of_memory, created_out);
  fs::create_directories(staging_);
}

StagingFolder::~StagingFolder() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

void StagingFolder::commit() {
  if (const auto problem = foreignAssetProblem(final_)) throw InputError({final_.string()}, "", *problem, kForeignHint);
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(final_, ec))) {
    int error = renameWith(staging_, final_, RENAME_NOREPLACE);
    if (unsupported(error)) error = renameWith(staging_, final_, 0);
    if (error == 0) {
      committed_ = true;
      return;
    }
    if (error != EEXIST && error != ENOTEMPTY) failRename(error, staging_, final_);
    // Made meanwhile (by hand: every bake of it holds the lock): replaced only if it may be.
    if (const auto problem = foreignAssetProblem(final_))
      throw InputError({final_.string()}, "", *problem, kForeignHint);
  }
  // One step: the previous asset and the new one change places, and the old one is removed from the hidden name.
  const int error = renameWith(staging_, final_, RENAME_EXCHANGE);
  if (error == 0) {
    committed_ = true;
    discard(staging_);
    return;
  }
  if (!unsupported(error)) failRename(error, staging_, final_);
  // No exchange on this filesystem: two renames, and tidyAssetFolder mends a kill between them.
  const fs::path aside = hidden(final_, "replaced");
  if (const int moved = renameWith(final_, aside, 0)) failRename(moved, final_, aside);
  if (const int placed = renameWith(staging_, final_, 0)) failRename(placed, staging_, final_);
  committed_ = true;
  discard(aside);
}

}  // namespace rockbake
