// The commit rule for asset folders (pipeline/asset_folder.h, docs/command-line.md,
// "What a bake may replace"), through the real executable: a bake replaces only
// what rockbake wrote, refuses anything else before any work, never leaves
// neither the previous asset nor the new one, and one process at a time writes
// an asset.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <regex>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/sha256.h"
#include "pipeline/asset_folder.h"
#include "pipeline/manifest.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::kSmallPreset;
using test::readBytes;
using test::runRockbake;
using test::startRockbake;
using test::TempDir;
using test::writeText;

// The folder's input hash when it holds a manifest whose every output is there with its size and
// SHA-256 (a complete asset); empty otherwise.
std::string completeAssetHash(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / kManifestFile, ec)) return {};
  const json manifest = json::parse(readBytes(dir / kManifestFile), nullptr, false);
  if (manifest.is_discarded() || !manifest.contains("outputs")) return {};
  for (const auto& output : manifest["outputs"]) {
    const fs::path file = dir / output["path"].get<std::string>();
    if (!fs::is_regular_file(file, ec) || fs::file_size(file) != output["size"].get<std::uintmax_t>() ||
        sha256File(file) != output["sha256"].get<std::string>())
      return {};
  }
  return manifest["inputs"]["input_hash"].get<std::string>();
}

std::set<std::string> namesIn(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

fs::path writePreset(const fs::path& dir, const std::string& name) {
  const fs::path file = dir / (name + ".yaml");
  std::string text = kSmallPreset;
  text.replace(text.find("name: small"), 11, "name: " + name);
  writeText(file, text);
  return file;
}

bool saysItSimulated(const std::string& output) {
  return output.find("rock voxels") != std::string::npos || output.find("cycle") != std::string::npos;
}

TEST(AssetFolder, ABakeNeverReplacesWhatItDidNotWrite) {
  TempDir dir;
  // A shared preset named `docs` baked with -o . deleted the user's ./docs/ and exited 0.
  const fs::path docs = writePreset(dir.path(), "docs");
  writeText(dir.path() / "docs" / "notes.md", "the user's own");
  const auto folder = runRockbake({"bake", docs.string(), "-o", dir.path().string(), "--no-mesh"});
  EXPECT_EQ(folder.exit_status, 2) << folder.output;
  EXPECT_NE(folder.output.find((dir.path() / "docs").string() +
                               ": is a folder rockbake did not write (it holds no manifest.json or failure.json)"),
            std::string::npos)
      << folder.output;
  EXPECT_NE(folder.output.find("move it away, bake into another folder (-o OUT)"), std::string::npos);
  EXPECT_FALSE(saysItSimulated(folder.output)) << "refused before any work: " << folder.output;
  EXPECT_EQ(readBytes(dir.path() / "docs" / "notes.md"), "the user's own");
  EXPECT_EQ(namesIn(dir.path()), (std::set<std::string>{"docs", "docs.yaml"})) << "nothing else written";

  // A file, and a symbolic link (even to an asset folder), are not asset folders either.
  const fs::path out = dir.path() / "out";
  writeText(out / "small", "a file named like the asset");
  const fs::path small = writePreset(dir.path(), "small");
  const auto file = runRockbake({"bake", small.string(), "-o", out.string(), "--no-mesh"});
  EXPECT_EQ(file.exit_status, 2) << file.output;
  EXPECT_NE(file.output.find("small: is a file, not an asset folder rockbake wrote"), std::string::npos) << file.output;
  EXPECT_EQ(readBytes(out / "small"), "a file named like the asset");
  fs::remove(out / "small");
  ASSERT_EQ(runRockbake({"bake", small.string(), "-o", (dir.path() / "elsewhere").string(), "--no-mesh"}).exit_status,
            0);
  fs::create_directory_symlink(dir.path() / "elsewhere" / "small", out / "small");
  const auto link = runRockbake({"bake", small.string(), "-o", out.string(), "--no-mesh"});
  EXPECT_EQ(link.exit_status, 2) << link.output;
  EXPECT_NE(link.output.find("small: is a symbolic link"), std::string::npos) << link.output;
  EXPECT_TRUE(fs::is_symlink(out / "small"));
  EXPECT_FALSE(completeAssetHash(dir.path() / "elsewhere" / "small").empty());

  // With several presets, one refused folder bakes none of them.
  fs::remove(out / "small");
  const auto several = runRockbake({"bake", small.string(), docs.string(), "-o", dir.path().string(), "--no-mesh"});
  EXPECT_EQ(several.exit_status, 2) << several.output;
  EXPECT_FALSE(fs::exists(dir.path() / "small"));
}

TEST(AssetFolder, ABakeReplacesItsOwnAssetsAndEmptyFolders) {
  TempDir dir;
  const fs::path small = writePreset(dir.path(), "small");
  const fs::path out = dir.path() / "out";
  fs::create_directories(out / "small");  // empty: nothing in it to lose
  ASSERT_EQ(runRockbake({"bake", small.string(), "-o", out.string(), "--no-mesh"}).exit_status, 0);
  const std::string first = completeAssetHash(out / "small");
  ASSERT_FALSE(first.empty());
  ASSERT_EQ(runRockbake({"bake", small.string(), "-o", out.string(), "--no-mesh", "--seed", "8"}).exit_status, 0);
  const std::string second = completeAssetHash(out / "small");
  EXPECT_FALSE(second.empty());
  EXPECT_NE(second, first);
  // A failed library job's folder (failure.json) is ours too.
  fs::remove_all(out / "small");
  writeText(out / "small" / kFailureFile, "{\"asset\": \"small\", \"status\": \"failed\", \"message\": \"x\"}\n");
  ASSERT_EQ(runRockbake({"bake", small.string(), "-o", out.string(), "--no-mesh"}).exit_status, 0);
  EXPECT_EQ(completeAssetHash(out / "small"), first);
  EXPECT_FALSE(fs::exists(out / "small" / kFailureFile));
  EXPECT_EQ(namesIn(out), std::set<std::string>{"small"}) << "no lock file or staging folder left";
}

// A library job named `readme` deleted the file ./readme and exited 0. Now the run is refused before any
// job bakes, naming the path.
TEST(AssetFolder, ALibraryRunWithAForeignJobFolderIsRefusedBeforeItStarts) {
  TempDir dir;
  writePreset(dir.path(), "small");
  writeText(dir.path() / "lib.yaml", "- preset: small.yaml\n  name: first\n- preset: small.yaml\n  name: readme\n");
  const fs::path out = dir.path() / "out";
  writeText(out / "readme", "read me");
  const auto result = runRockbake({"library", (dir.path() / "lib.yaml").string(), "-o", out.string(), "--no-mesh"});
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find((out / "readme").string() + ": is a file, not an asset folder rockbake wrote"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(readBytes(out / "readme"), "read me");
  EXPECT_EQ(namesIn(out), std::set<std::string>{"readme"}) << "no job baked, no index written";
}

TEST(AssetFolder, ResumeRefusesAForeignFolderToo) {
  TempDir dir;
  const fs::path small = writePreset(dir.path(), "small");
  ASSERT_EQ(runRockbake(
                {"bake", small.string(), "-o", (dir.path() / "b").string(), "--no-mesh", "--checkpoint-every", "0.25"})
                .exit_status,
            0);
  writeText(dir.path() / "c" / "small" / "keep.txt", "mine");
  const auto resumed = runRockbake({"resume", (dir.path() / "b" / "small" / "checkpoints" / "0.25.rbk").string(), "-o",
                                    (dir.path() / "c").string(), "--no-mesh"});
  EXPECT_EQ(resumed.exit_status, 2) << resumed.output;
  EXPECT_NE(resumed.output.find("small: is a folder rockbake did not write"), std::string::npos) << resumed.output;
  EXPECT_FALSE(saysItSimulated(resumed.output)) << resumed.output;
  EXPECT_EQ(namesIn(dir.path() / "c" / "small"), std::set<std::string>{"keep.txt"});
}

// OUT given as a file was exit 1 with "filesystem error: cannot remove: Not a directory".
TEST(AssetFolder, OutGivenAsAFileIsExit2) {
  TempDir dir;
  const fs::path small = writePreset(dir.path(), "small");
  writeText(dir.path() / "lib.yaml", "- preset: small.yaml\n");
  writeText(dir.path() / "outfile", "not a folder");
  const std::vector<std::vector<std::string>> commands = {
      {"bake", small.string(), "--no-mesh", "-o"},
      {"bake", small.string(), "--no-mesh", "-o", "sub"},
      {"library", (dir.path() / "lib.yaml").string(), "--no-mesh", "-o"},
  };
  for (auto args : commands) {
    const bool sub = args.back() == "sub";
    if (sub) args.pop_back();
    args.push_back((dir.path() / "outfile").string() + (sub ? "/sub" : ""));
    const auto result = runRockbake(args);
    EXPECT_EQ(result.exit_status, 2) << result.output;
    const std::string said = (dir.path() / "outfile").string() +
                             (sub ? "/sub: " + (dir.path() / "outfile").string() + " " : ": ") +
                             "is a file, not a folder";
    EXPECT_NE(result.output.find(said), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("give -o a folder to write the assets in"), std::string::npos) << result.output;
    EXPECT_EQ(result.output.find("filesystem error"), std::string::npos) << result.output;
  }
  EXPECT_EQ(readBytes(dir.path() / "outfile"), "not a folder");
}

// ---- the studio's bake final, through its HTTP API ----

class Studio {
 public:
  Studio(const fs::path& preset, const fs::path& out) : log_(out.parent_path() / "studio.log") {
    child_ = test::startRockbake({"studio", preset.string(), "--port", "0", "--resolution", "16", "-o", out.string()},
                                 log_);
    const std::regex listening(R"(studio: http://127\.0\.0\.1:(\d+)/)");
    std::smatch match;
    // The address it listens on, printed once it does (or never, when it failed to start).
    for (int i = 0; i < 6000 && !child_->poll(); ++i) {
      const std::string said = test::readBytes(log_);
      if (std::regex_search(said, match, listening)) {
        port_ = std::stoi(match[1]);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  ~Studio() {
    ::kill(child_->pid(), SIGINT);
    child_->wait();
  }
  int port() const { return port_; }

  // The response's body (status line and headers dropped).
  std::string request(const std::string& method, const std::string& path, const std::string& body = "") const {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(std::uint16_t(port_));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
      ::close(fd);
      return {};
    }
    const std::string host = "127.0.0.1:" + std::to_string(port_);
    std::string text = method + " " + path + " HTTP/1.1\r\nHost: " + host + "\r\nConnection: close\r\n";
    if (method == "POST")
      text += "Content-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) + "\r\n";
    text += "\r\n" + body;
    ::send(fd, text.data(), text.size(), MSG_NOSIGNAL);
    std::string response;
    char buffer[4096];
    for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) response.append(buffer, std::size_t(n));
    ::close(fd);
    const std::size_t end = response.find("\r\n\r\n");
    return end == std::string::npos ? std::string() : response.substr(end + 4);
  }

 private:
  fs::path log_;
  std::unique_ptr<ChildProcess> child_;
  int port_ = 0;
};

TEST(AssetFolder, TheStudiosBakeFinalRefusesAForeignFolder) {
  TempDir dir;
  const fs::path small = writePreset(dir.path(), "small");
  const fs::path out = dir.path() / "out";
  writeText(out / "small" / "keep.txt", "mine");
  const Studio studio(small, out);
  ASSERT_GT(studio.port(), 0) << "the studio did not say where it listens";
  studio.request("POST", "/api/control", R"({"action": "step"})");  // the final bake bakes the current time
  const std::string started = studio.request("POST", "/api/bake", "{}");
  EXPECT_NE(started.find("asset_dir"), std::string::npos) << started;
  json bake;
  for (int i = 0; i < 600; ++i) {
    const json state = json::parse(studio.request("GET", "/api/state"), nullptr, false);
    ASSERT_FALSE(state.is_discarded());
    bake = state["bake"];
    if (bake["state"] != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(bake["state"], "failed") << bake.dump();
  EXPECT_NE(bake["message"].get<std::string>().find("small: is a folder rockbake did not write"), std::string::npos)
      << bake.dump();
  EXPECT_EQ(namesIn(out), std::set<std::string>{"small"});
  EXPECT_EQ(namesIn(out / "small"), std::set<std::string>{"keep.txt"});
}

// ---- one writer at a time ----

TEST(AssetFolder, ALiveHolderIsRefusedAndADeadOnesLockTakenOver) {
  TempDir dir;
  const fs::path small = writePreset(dir.path(), "small");
  const fs::path out = dir.path() / "out";
  {
    const AssetLock held(out / "small");  // this test process is the other bake
    const auto refused = runRockbake({"bake", small.string(), "-o", out.string(), "--no-mesh"});
    EXPECT_EQ(refused.exit_status, 2) << refused.output;
    EXPECT_NE(refused.output.find("small: is being written by pid " + std::to_string(::getpid()) + " on host "),
              std::string::npos)
        << refused.output;
    EXPECT_NE(refused.output.find("wait for that bake to finish"), std::string::npos) << refused.output;
    EXPECT_FALSE(saysItSimulated(refused.output)) << refused.output;
  }
  // What a killed bake leaves: its lock file (no process holds it now) and hidden folders.
  writeText(out / ".small.lock", "pid 999999 on host gone, since 2020-01-01T00:00:00Z\n");
  writeText(out / ".small.baking-999999" / "rock.vdb", "half written");
  writeText(out / ".small.replaced-999998" / "stats.json", "half removed");
  const auto taken = runRockbake({"bake", small.string(), "-o", out.string(), "--no-mesh"});
  EXPECT_EQ(taken.exit_status, 0) << taken.output;
  EXPECT_FALSE(completeAssetHash(out / "small").empty());
  EXPECT_EQ(namesIn(out), std::set<std::string>{"small"});
}

// A kill at every rename or removal of a bake replacing an asset leaves the previous asset or the new
// one in place, complete. Where the filesystem cannot exchange two folders (NFS; simulated), the commit
// is two renames: a kill between them leaves the new asset, complete, under its hidden name, and the
// next run puts it in place.
TEST(AssetFolder, AKillAtEveryPointLeavesThePreviousAssetOrTheNew) {
  TempDir dir;
  const fs::path small = writePreset(dir.path(), "small");
  const fs::path pristine = dir.path() / "pristine";
  ASSERT_EQ(runRockbake({"bake", small.string(), "-o", pristine.string(), "--no-mesh", "--seed", "1"}).exit_status, 0);
  ASSERT_EQ(runRockbake({"bake", small.string(), "-o", (dir.path() / "fresh").string(), "--no-mesh", "--seed", "2"})
                .exit_status,
            0);
  const std::string previous = completeAssetHash(pristine / "small");
  const std::string next = completeAssetHash(dir.path() / "fresh" / "small");
  ASSERT_NE(previous, next);
  const fs::path out = dir.path() / "out";
  const std::vector<std::string> bake = {"bake", small.string(), "-o", out.string(), "--no-mesh", "--seed", "2"};
  for (const bool exchange : {true, false}) {
    int n = 1;
    for (; n < 200; ++n) {
      fs::remove_all(out);
      fs::create_directories(out);
      fs::copy(pristine / "small", out / "small", fs::copy_options::recursive);
      const std::string prefix = std::string("ASAN_OPTIONS=verify_asan_link_order=0 LD_PRELOAD='") +
                                 ROCKBAKE_KILL_AT_PRELOAD + "' ROCKBAKE_KILL_UNDER='" + out.string() +
                                 "' ROCKBAKE_KILL_AT=" + std::to_string(n) +
                                 (exchange ? " " : " ROCKBAKE_NO_EXCHANGE=1 ");
      const auto killed = test::runRockbakeUnder(prefix, bake);
      const std::string found = completeAssetHash(out / "small");
      if (killed.exit_status == 0) {  // n is past the bake's last change
        EXPECT_EQ(found, next);
        break;
      }
      ASSERT_EQ(killed.exit_status, 128 + SIGKILL) << killed.output;
      if (exchange || !found.empty()) {
        EXPECT_TRUE(found == previous || found == next)
            << "killed before change " << n << ": neither asset is whole in place";
      } else {
        bool kept = false;  // between the two renames: the new asset whole under its hidden name
        for (const auto& name : namesIn(out))
          kept = kept || (name.rfind(".small.baking-", 0) == 0 && completeAssetHash(out / name) == next);
        EXPECT_TRUE(kept) << "killed before change " << n << ": the new asset is lost";
      }
      const auto mended = runRockbake(bake);
      ASSERT_EQ(mended.exit_status, 0) << mended.output;
      EXPECT_EQ(completeAssetHash(out / "small"), next);
      EXPECT_EQ(namesIn(out), std::set<std::string>{"small"}) << "after change " << n;
    }
    EXPECT_GT(n, 8) << "the bake made too few changes for the test to mean anything";
    EXPECT_LT(n, 200) << "the bake never finished";
  }
}

// ---- two runs into one OUT ----

// True once OUT holds the staging folder of a bake of `name` (it is baking it, under its lock).
bool waitForStaging(const fs::path& out, const std::string& name, ChildProcess& child) {
  for (int i = 0; i < 12000; ++i) {
    std::error_code ec;
    if (fs::is_directory(out, ec))
      for (const auto& entry : fs::directory_iterator(out, ec))
        if (entry.path().filename().string().rfind("." + name + ".baking-", 0) == 0) return true;
    if (child.poll()) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// Job x bakes quickly, job y slowly (about 2 s).
fs::path writeTwoJobLibrary(const TempDir& dir) {
  writePreset(dir.path(), "small");
  writeText(dir.path() / "lib.yaml",
            "- preset: small.yaml\n  name: x\n"
            "- preset: small.yaml\n  name: y\n  wedges: [{name: slow, set: {grid.resolution: 128, time: 3}}]\n");
  return dir.path() / "lib.yaml";
}

// A second run of a library into the OUT a first run is baking wrote failure.json into the first run's
// finished assets (here: a run whose jobs all fail, started while the first bakes its last job). Now it is
// refused before it starts, naming the run that holds the asset.
TEST(AssetFolder, TwoLibraryRunsIntoOneOutDoNotCorruptEachOther) {
  TempDir dir;
  const fs::path lib = writeTwoJobLibrary(dir);
  const fs::path out = dir.path() / "out";
  const auto first = startRockbake({"library", lib.string(), "-o", out.string(), "--no-mesh"}, dir.path() / "a.log");
  ASSERT_TRUE(waitForStaging(out, "y-slow", *first)) << readBytes(dir.path() / "a.log");
  const auto second = runRockbake({"library", lib.string(), "-o", out.string(), "--no-mesh", "--set", "time=-1"});
  EXPECT_EQ(second.exit_status, 2) << second.output;
  EXPECT_NE(second.output.find("y-slow: is being written by pid " + std::to_string(first->pid()) + " on host "),
            std::string::npos)
      << second.output;
  EXPECT_EQ(exitCode(first->wait()), 0) << readBytes(dir.path() / "a.log");
  for (const char* job : {"x", "y-slow"}) {
    EXPECT_FALSE(completeAssetHash(out / job).empty()) << job;
    EXPECT_FALSE(fs::exists(out / job / kFailureFile)) << job;
  }
  const json index = json::parse(readBytes(out / "index.json"));
  EXPECT_EQ(index["counts"]["ok"], 2) << index.dump();
}

// A job whose asset another process took meanwhile fails, naming it, and writes nothing into it; the run
// goes on, and a later run bakes it.
TEST(AssetFolder, AJobWhoseAssetIsBeingWrittenElsewhereFailsAndWritesNothing) {
  TempDir dir;
  writePreset(dir.path(), "small");
  writeText(dir.path() / "lib.yaml",
            "- preset: small.yaml\n  name: first\n  wedges: [{name: slow, set: {grid.resolution: 128, time: 3}}]\n"
            "- preset: small.yaml\n  name: last\n");
  const fs::path out = dir.path() / "out";
  const std::vector<std::string> args = {"library", (dir.path() / "lib.yaml").string(), "-o", out.string(),
                                         "--no-mesh"};
  const auto run = startRockbake(args, dir.path() / "run.log");
  ASSERT_TRUE(waitForStaging(out, "first-slow", *run)) << readBytes(dir.path() / "run.log");
  {
    const AssetLock elsewhere(out / "last");
    EXPECT_EQ(exitCode(run->wait()), 1);
    const std::string log = readBytes(dir.path() / "run.log");
    EXPECT_NE(log.find("last: is being written by pid " + std::to_string(::getpid())), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(out / "last")) << "nothing written into an asset another process holds";
    EXPECT_FALSE(completeAssetHash(out / "first-slow").empty());
  }
  const auto again = runRockbake(args);
  EXPECT_EQ(again.exit_status, 0) << again.output;
  EXPECT_FALSE(completeAssetHash(out / "last").empty());
  EXPECT_EQ(json::parse(readBytes(out / "index.json"))["timings"]["this_run"]["first-slow"], "skipped-resumed");
}

}  // namespace
}  // namespace rockbake
