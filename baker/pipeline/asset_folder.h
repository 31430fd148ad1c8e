// The commit rule for asset folders (docs/command-line.md, "What a bake may
// replace"): what `bake`, `library`, `resume` and the studio's bake final may
// do to OUT/<name>, and how a finished bake takes its place.
//
// - OUT/<name> is replaced only when it is absent, an empty folder, or a folder
//   rockbake wrote: one holding manifest.json (a finished bake) or failure.json
//   (a library job that failed). A file, a symbolic link or any other folder
//   there is refused with an InputError naming it (exit 2), before any work.
//   OUT itself must be a folder, or be creatable as one.
// - One process at a time writes OUT/<name>: it holds OUT/.<name>.lock, an
//   open-file-description lock the kernel (or the NFS server) drops when the
//   process dies, and the file names the holder (pid, host, start). A live
//   holder is refused with an InputError naming it; a dead one's lock is taken
//   over.
// - A bake writes into OUT/.<name>.baking-<pid> and commits by exchanging it
//   with OUT/<name> in one step (renameat2 RENAME_EXCHANGE), so a kill at any
//   point leaves the previous asset or the new one. Where the filesystem cannot
//   exchange (NFS), the old folder is renamed aside first; a kill between the
//   two renames leaves both under hidden names, and the next rockbake to take
//   the asset's lock finishes the commit (or puts the previous asset back).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "platform/abnormal_exit.h"

namespace rockbake {

// Throws InputError naming `out_dir` when it, or a folder on its way, is a
// file: assets cannot be written under it.
void checkOutFolder(const std::filesystem::path& out_dir);

// Why OUT/<name> may not be replaced by a bake ("is a folder rockbake did not
// write …"), or nothing when it may.
std::optional<std::string> foreignAssetProblem(const std::filesystem::path& asset_dir);

// Who holds OUT/.<name>.lock now ("pid 123 on host n1, since …"), or nothing
// when no live process does.
std::optional<std::string> assetLockHolder(const std::filesystem::path& asset_dir);

// What a caller checks before any work, for each asset it will write: OUT is
// a folder, OUT/<name> may be replaced and no live process writes it. Throws
// InputError naming the path and what to do.
void checkAssetWritable(const std::filesystem::path& asset_dir);

// OUT/.<name>.lock, held while it lives. OUT is created when missing.
class AssetLock {
 public:
  // Throws InputError naming the holder when a live process holds it.
  explicit AssetLock(const std::filesystem::path& asset_dir);
  ~AssetLock();  // the lock file is removed, then the lock dropped
  AssetLock(const AssetLock&) = delete;
  AssetLock& operator=(const AssetLock&) = delete;

  const std::filesystem::path& assetDir() const { return asset_dir_; }
  bool createdOut() const { return created_out_; }  // OUT did not exist before: removed when left empty

 private:
  std::filesystem::path asset_dir_, file_;
  int fd_ = -1;
  bool created_out_ = false;
  std::unique_ptr<OnAbnormalExit> on_abnormal_exit_;  // the lock file goes with the staging folder
};

// Under the asset's lock: finishes a commit that was cut short (a finished
// bake still under its hidden name goes into place, else a previous asset
// renamed aside comes back) and removes what killed bakes of this asset left.
void tidyAssetFolder(const AssetLock& lock);

// A bake's hidden folder beside its asset: created empty (after the lock is
// taken, tidyAssetFolder and the foreign check), removed on destruction unless
// committed. OUT, when the bake created it, goes too if it is left empty.
class StagingFolder {
 public:
  // `lock`: the asset's lock when the caller holds it (a library job, which
  // keeps it for its failure record); nullptr: taken here. `out_of_memory`:
  // what to say should the process end without unwinding
  // (platform/abnormal_exit.h), which removes the folder then too.
  StagingFolder(const std::filesystem::path& asset_dir, const std::string& out_of_memory, const AssetLock* lock);
  ~StagingFolder();
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const std::filesystem::path& path() const { return staging_; }

  // Puts the folder in the asset's place (exchanged with the previous asset,
  // which is then removed). Throws InputError when OUT/<name> became foreign
  // meanwhile.
  void commit();

 private:
  std::filesystem::path final_, staging_;
  bool committed_ = false;
  std::unique_ptr<AssetLock> own_lock_;
  std::unique_ptr<OnAbnormalExit> on_abnormal_exit_;
};

}  // namespace rockbake
