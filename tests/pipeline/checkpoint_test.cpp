// Checkpoints and resume (docs/libraries.md), through the real executable: a resumed
// bake equals the uninterrupted one byte for byte; an edit at the checkpoint
// equals the same keyframe baked from the start; grid, shape, seed and
// resolution cannot change; a truncated, corrupt or foreign file is a clear error,
// and so is one whose checksum holds but whose header does not fit its arrays;
// a file of gigabytes is refused from its first bytes, a FIFO or device at once.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/sha256.h"
#include "pipeline/checkpoint.h"
#include "sim/checkpoint_format.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using test::readBytes;
using test::runRockbake;
using test::TempDir;

// The small box preset for 1.5 units of time: 18 cycles of h = 2 / 24.
fs::path writeSmall(const TempDir& dir) {
  const fs::path file = dir.path() / "small.yaml";
  test::writeText(file, std::string(test::kSmallPreset) + "colluvium: {yield: 0.8}\n");
  return file;
}

const std::vector<std::string> kLong = {"--set", "time=1.5", "--no-render"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(Checkpoint, ResumedWithoutEditsEqualsTheUninterruptedBake) {
  TempDir dir;
  const fs::path preset = writeSmall(dir);
  const auto straight = runRockbake(with({"bake", preset.string(), "-o", (dir.path() / "a").string()}, kLong));
  ASSERT_EQ(straight.exit_status, 0) << straight.output;
  const auto checkpointed = runRockbake(
      with({"bake", preset.string(), "-o", (dir.path() / "b").string(), "--checkpoint-every", "0.5"}, kLong));
  ASSERT_EQ(checkpointed.exit_status, 0) << checkpointed.output;
  const fs::path checkpoints = dir.path() / "b" / "small" / "checkpoints";
  ASSERT_TRUE(fs::exists(checkpoints / "0.5.rbk")) << checkpointed.output;
  ASSERT_TRUE(fs::exists(checkpoints / "1.rbk"));
  EXPECT_FALSE(fs::exists(checkpoints / "1.5.rbk")) << "no checkpoint of the finished state";

  const auto resumed =
      runRockbake({"resume", (checkpoints / "0.5.rbk").string(), "-o", (dir.path() / "c").string(), "--no-render"});
  ASSERT_EQ(resumed.exit_status, 0) << resumed.output;
  for (const char* file : {"rock.vdb", "rock.ply", "rock.glb", "asset.json"}) {
    const std::string a = readBytes(dir.path() / "a" / "small" / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, readBytes(dir.path() / "b" / "small" / file)) << file << ": checkpointing changed the bake";
    EXPECT_EQ(a, readBytes(dir.path() / "c" / "small" / file)) << file << ": the resumed bake differs";
  }
}

// The stage switches are options, not edits of the preset: a checkpoint written by a bake with
// --no-textures (and --no-mesh) resumes, with or without them, and equals the uninterrupted bake.
TEST(Checkpoint, ResumesWhateverTheStageSwitches) {
  TempDir dir;
  const fs::path preset = dir.path() / "small.yaml";
  test::writeText(preset, std::string(test::kSmallPreset) + "colluvium: {yield: 0.8}\ntexture: {size: 256}\n");
  const auto straight =
      runRockbake(with({"bake", preset.string(), "-o", (dir.path() / "a").string(), "--no-textures"}, kLong));
  ASSERT_EQ(straight.exit_status, 0) << straight.output;
  const auto checkpointed = runRockbake(
      with({"bake", preset.string(), "-o", (dir.path() / "b").string(), "--no-textures", "--checkpoint-every", "0.5"},
           kLong));
  ASSERT_EQ(checkpointed.exit_status, 0) << checkpointed.output;
  const fs::path checkpoint = dir.path() / "b" / "small" / "checkpoints" / "0.5.rbk";
  for (const std::vector<std::string>& switches :
       {std::vector<std::string>{"--no-textures"}, std::vector<std::string>{"--no-mesh"}, std::vector<std::string>{}}) {
    const fs::path out = dir.path() / ("c" + std::to_string(switches.size()) + (switches.empty() ? "" : switches[0]));
    const auto resumed =
        runRockbake(with({"resume", checkpoint.string(), "-o", out.string(), "--no-render"}, switches));
    ASSERT_EQ(resumed.exit_status, 0) << resumed.output;
    const std::string what = switches.empty() ? "no switch" : switches[0];
    const auto cycles = [](const fs::path& asset) {
      return nlohmann::json::parse(readBytes(asset / "stats.json"))["cycles"];
    };
    EXPECT_EQ(cycles(dir.path() / "a" / "small"), cycles(out / "small")) << what;
    if (what != "--no-mesh") {  // without meshes rock.vdb holds the voxels' own level set (docs/formats.md)
      EXPECT_EQ(readBytes(dir.path() / "a" / "small" / "rock.vdb"), readBytes(out / "small" / "rock.vdb")) << what;
    }
    EXPECT_EQ(fs::exists(out / "small" / "textures"), switches.empty());
  }
}

TEST(Checkpoint, AnEditAtTheCheckpointEqualsTheSameKeyframeFromTheStart) {
  TempDir dir;
  const fs::path preset = writeSmall(dir);
  ASSERT_EQ(runRockbake(with({"bake", preset.string(), "-o", (dir.path() / "b").string(), "--checkpoint-every", "0.5",
                              "--no-mesh"},
                             {"--set", "time=1.5"}))
                .exit_status,
            0);
  const std::string points = "[[0, 0.3], [0.5, 2.0], [1, 0.5]]";
  const auto resumed = runRockbake({"resume", (dir.path() / "b" / "small" / "checkpoints" / "0.5.rbk").string(), "-o",
                                    (dir.path() / "c").string(), "--no-mesh", "--set", "durability.points=" + points,
                                    "--set", "response={power: 2.0}"});
  ASSERT_EQ(resumed.exit_status, 0) << resumed.output;
  // The checkpoint's time is cycle 6 at h = 2 / 24, exactly as the simulation computes it.
  const std::string at = fmt::format("{}", 6 * (2.0 / 24));
  const auto from_start =
      runRockbake({"bake", preset.string(), "-o", (dir.path() / "d").string(), "--no-mesh", "--set", "time=1.5",
                   "--set", "durability.keyframes=[{at: " + at + ", points: " + points + ", response: {power: 2.0}}]"});
  ASSERT_EQ(from_start.exit_status, 0) << from_start.output;
  const std::string resumed_vdb = readBytes(dir.path() / "c" / "small" / "rock.vdb");
  EXPECT_EQ(resumed_vdb, readBytes(dir.path() / "d" / "small" / "rock.vdb"));
  EXPECT_NE(resumed_vdb, readBytes(dir.path() / "b" / "small" / "rock.vdb")) << "the edit changed nothing";
  // The resumed asset's manifest records a preset that reproduces it.
  const std::string manifest = readBytes(dir.path() / "c" / "small" / "manifest.json");
  EXPECT_NE(manifest.find("durability.keyframes="), std::string::npos) << manifest;
}

TEST(Checkpoint, GridShapeSeedAndResolutionCannotChangeOnResume) {
  TempDir dir;
  const fs::path preset = writeSmall(dir);
  ASSERT_EQ(runRockbake(
                {"bake", preset.string(), "-o", (dir.path() / "b").string(), "--checkpoint-every", "0.25", "--no-mesh"})
                .exit_status,
            0);
  const std::string checkpoint = (dir.path() / "b" / "small" / "checkpoints" / "0.25.rbk").string();
  for (const std::string set : {"grid.resolution=32", "shape.box.size=[1, 1, 1]", "seed=9", "grid.size=[3, 3, 3]"}) {
    const auto r = runRockbake({"resume", checkpoint, "-o", (dir.path() / "c").string(), "--set", set});
    EXPECT_EQ(r.exit_status, 2) << set << "\n" << r.output;
    EXPECT_NE(r.output.find("a resumed bake cannot change '" + set.substr(0, set.find('=')) + "'"), std::string::npos)
        << r.output;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "c")) << "a refused resume wrote something";
  // Allowed, but a value the preset reader refuses is still refused.
  const auto bad = runRockbake({"resume", checkpoint, "-o", (dir.path() / "c").string(), "--set", "colluvium.yield=7"});
  EXPECT_EQ(bad.exit_status, 2) << bad.output;
  EXPECT_NE(bad.output.find("colluvium.yield"), std::string::npos) << bad.output;
}

TEST(Checkpoint, TruncatedCorruptAndForeignFilesAreClearErrors) {
  TempDir dir;
  const fs::path preset = writeSmall(dir);
  ASSERT_EQ(runRockbake(
                {"bake", preset.string(), "-o", (dir.path() / "b").string(), "--checkpoint-every", "0.25", "--no-mesh"})
                .exit_status,
            0);
  const std::string whole = readBytes(dir.path() / "b" / "small" / "checkpoints" / "0.25.rbk");
  ASSERT_GT(whole.size(), 1000u);
  const auto resumeOf = [&](const std::string& name, const std::string& bytes) {
    test::writeText(dir.path() / name, bytes);
    return runRockbake({"resume", (dir.path() / name).string(), "-o", (dir.path() / "c").string(), "--no-mesh"});
  };
  const auto truncated = resumeOf("truncated.rbk", whole.substr(0, whole.size() / 2));
  EXPECT_EQ(truncated.exit_status, 2);
  EXPECT_NE(truncated.output.find("truncated.rbk: the checkpoint is truncated or corrupt"), std::string::npos)
      << truncated.output;
  std::string flipped = whole;
  flipped[whole.size() / 2] = char(flipped[whole.size() / 2] ^ 0x10);
  const auto corrupt = resumeOf("corrupt.rbk", flipped);
  EXPECT_EQ(corrupt.exit_status, 2);
  EXPECT_NE(corrupt.output.find("checksum does not match"), std::string::npos) << corrupt.output;
  const auto foreign = resumeOf("foreign.rbk", readBytes(preset));
  EXPECT_EQ(foreign.exit_status, 2);
  EXPECT_NE(foreign.output.find("not a rockbake checkpoint"), std::string::npos) << foreign.output;
  EXPECT_FALSE(fs::exists(dir.path() / "c" / "small")) << "a bad checkpoint left an asset folder";
  // And the whole file still resumes.
  EXPECT_EQ(resumeOf("whole.rbk", whole).exit_status, 0);
}

// A checkpoint's parts past its checksum: what a file edited by hand (or made
// to pass the checksum) holds.
struct Parts {
  nlohmann::ordered_json header;
  std::string arrays;  // everything after the header, without the checksum
};

Parts split(const std::string& whole) {
  std::uint64_t size = 0;
  std::memcpy(&size, whole.data() + 12, sizeof size);
  return {nlohmann::ordered_json::parse(whole.substr(20, size)),
          whole.substr(20 + size, whole.size() - 64 - 20 - size)};
}

// `whole` with the header as `header_text`, the arrays as `arrays` and a valid checksum.
std::string joined(const std::string& whole, const std::string& header_text, const std::string& arrays) {
  std::string out = whole.substr(0, 12);
  const std::uint64_t size = header_text.size();
  out.append(reinterpret_cast<const char*>(&size), sizeof size);
  out += header_text + arrays;
  return out + sha256Hex(out);
}

std::string bakeOneCheckpoint(const TempDir& dir) {
  const fs::path preset = writeSmall(dir);
  const auto bake = runRockbake(
      {"bake", preset.string(), "-o", (dir.path() / "b").string(), "--checkpoint-every", "0.25", "--no-mesh"});
  EXPECT_EQ(bake.exit_status, 0) << bake.output;
  return readBytes(dir.path() / "b" / "small" / "checkpoints" / "0.25.rbk");
}

// The inputs in fuzz/regressions/fuzz_checkpoint/: each passed the checksum, and was read into a
// snapshot the simulation refused (exit 1, a message without the file), or allocated for a size the
// file does not hold, or crashed.
TEST(Checkpoint, AValidChecksumOverAHeaderThatDoesNotFitItsArraysIsRefused) {
  TempDir dir;
  const std::string whole = bakeOneCheckpoint(dir);
  ASSERT_FALSE(whole.empty());
  const Parts parts = split(whole);
  const auto edited = [&](const std::function<void(nlohmann::ordered_json&)>& edit) {
    nlohmann::ordered_json header = parts.header;
    edit(header);
    return joined(whole, header.dump(), parts.arrays);
  };
  const auto layout = [&](int nx, int ny, int nz) {
    return edited([&](auto& h) { h["layout"]["nx"] = nx, h["layout"]["ny"] = ny, h["layout"]["nz"] = nz; });
  };
  const std::size_t columns = std::size_t(parts.header["layout"]["nx"]) * std::size_t(parts.header["layout"]["ny"]);
  std::string three_columns = parts.arrays.substr(0, parts.arrays.size() - 8 - 8 * columns);
  const std::uint64_t three = 3;
  three_columns.append(reinterpret_cast<const char*>(&three), 8).append(24, '\0');
  std::string bad_material = parts.arrays;
  bad_material[8] = 7;
  std::string preset = parts.header["preset"].dump();
  preset.insert(1, "\"deep\": " + std::string(1000000, '[') + std::string(1000000, ']') + ",");
  std::string deep = parts.header.dump();
  deep.replace(deep.find(parts.header["preset"].dump()), parts.header["preset"].dump().size(), preset);

  const std::vector<std::pair<std::string, std::string>> cases = {
      // -1 × -1 × 1 cells wrap to 1; the spans' rows to 2^64 - 1 (std::length_error).
      {layout(-1, -1, 1), "layout.nx is -1, not a whole number from 1 to"},
      // No cells, and 2^32 rows (16 GiB) allocated for the spans.
      {layout(0, 1 << 30, 4), "layout.nx is 0, not a whole number"},
      {layout(1000, 1000, 1000), "grid is 1000×1000×1000, more cells than its"},
      // A float beyond int, cast to one (undefined behaviour).
      {edited([](auto& h) { h["layout"]["nx"] = 1e30; }), "layout.nx is 1e+30"},
      {edited([](auto& h) { h["overrides"]["seed"] = -1.5e300; }), "overrides.seed is -1.5e+300"},
      {edited([](auto& h) { h["layout"]["h"] = 0; }), "layout.h is 0, not a finite positive number"},
      // The simulation refused these at resume: "simulation snapshot: its grids do not match its layout",
      // "colluvium accumulators: 3 columns for a grid of ...", and a JSON type error after the simulation.
      {edited([](auto& h) { h["cycle"] = -5; }), "cycle is -5"},
      {joined(whole, parts.header.dump(), three_columns), "colluvium accumulators are not one per column"},
      {edited([](auto& h) { h["cycles"] = "none"; }), "cycles is not a list"},
      {joined(whole, parts.header.dump(), bad_material), "a cell's material is 7"},
      // Copying and printing JSON recurse: a million levels overflowed the stack.
      {joined(whole, deep, parts.arrays), "nests deeper than 64 levels"},
  };
  for (const auto& [bytes, problem] : cases) {
    try {
      parseCheckpoint(bytes, "edited.rbk");
      ADD_FAILURE() << "read: " << problem;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "edited.rbk");
      EXPECT_NE(e.problem().find("the checkpoint is corrupt ("), std::string::npos) << e.what();
      EXPECT_NE(e.problem().find(problem), std::string::npos) << e.what();
    }
  }
  // Through the executable: exit 2 naming the file (the deep one was a crash), and nothing written.
  test::writeText(dir.path() / "deep.rbk", joined(whole, deep, parts.arrays));
  const auto resumed = runRockbake({"resume", (dir.path() / "deep.rbk").string(), "-o", (dir.path() / "c").string()});
  EXPECT_EQ(resumed.exit_status, 2) << resumed.output;
  EXPECT_NE(resumed.output.find("deep.rbk: the checkpoint is corrupt (its header nests deeper than 64 levels)"),
            std::string::npos)
      << resumed.output;
  EXPECT_FALSE(fs::exists(dir.path() / "c"));
  // The unedited bytes, put together the same way, still read.
  EXPECT_NO_THROW(parseCheckpoint(joined(whole, parts.header.dump(), parts.arrays), "whole.rbk"));
}

#if defined(__SANITIZE_ADDRESS__)
#define SKIP_UNDER_ASAN() GTEST_SKIP() << "AddressSanitizer reserves more address space than ulimit -v allows"
#else
#define SKIP_UNDER_ASAN() (void)0
#endif

// A 2 GiB sparse file was read whole (2.1 GB of memory) before its magic bytes were looked at. Under
// 600 MiB of address space, reading it whole is an out-of-memory exit 1; refused from its first bytes,
// it is exit 2. So is a real checkpoint's header followed by far more bytes than its grid can hold.
TEST(Checkpoint, AHugeFileIsRefusedFromItsFirstBytes) {
  SKIP_UNDER_ASAN();
  TempDir dir;
  const std::string whole = bakeOneCheckpoint(dir);
  ASSERT_FALSE(whole.empty());
  const std::uintmax_t two_gib = std::uintmax_t(2) << 30;
  const auto resumeUnderLimit = [&](const fs::path& file) {
    return test::runRockbakeUnder("ulimit -v 614400; ", {"resume", file.string(), "-o", (dir.path() / "c").string()});
  };
  const fs::path foreign = dir.path() / "sparse.rbk";
  test::writeText(foreign, "");
  fs::resize_file(foreign, two_gib);
  const auto refused = resumeUnderLimit(foreign);
  EXPECT_EQ(refused.exit_status, 2) << refused.output;
  EXPECT_NE(refused.output.find("sparse.rbk: not a rockbake checkpoint"), std::string::npos) << refused.output;

  const Parts parts = split(whole);
  const fs::path padded = dir.path() / "padded.rbk";
  test::writeText(padded, whole.substr(0, 20 + parts.header.dump().size()));
  fs::resize_file(padded, two_gib);
  const auto too_big = resumeUnderLimit(padded);
  EXPECT_EQ(too_big.exit_status, 2) << too_big.output;
  EXPECT_NE(too_big.output.find("padded.rbk: the checkpoint is corrupt (the file is 2147483648 bytes; a checkpoint "
                                "of its grid holds at most"),
            std::string::npos)
      << too_big.output;
  EXPECT_FALSE(fs::exists(dir.path() / "c"));
  // The bound is not below any real checkpoint: the whole one, and every shorter cut of its header, are
  // judged by their content as before.
  test::writeText(dir.path() / "whole.rbk", whole);
  EXPECT_EQ(resumeUnderLimit(dir.path() / "whole.rbk").exit_status, 0);
  for (const std::size_t cut : {std::size_t(4), std::size_t(19), std::size_t(20) + 10, whole.size() - 1}) {
    test::writeText(dir.path() / "cut.rbk", whole.substr(0, cut));
    const auto result = runRockbake({"resume", (dir.path() / "cut.rbk").string(), "-o", (dir.path() / "c").string()});
    EXPECT_EQ(result.exit_status, 2) << cut << ": " << result.output;
    EXPECT_NE(result.output.find("cut.rbk: "), std::string::npos) << result.output;
  }
}

// A FIFO with no writer would block the read for ever, /dev/zero never ends: both refused at once, unread.
TEST(Checkpoint, AFifoOrADeviceIsRefusedAtOnce) {
  TempDir dir;
  const fs::path fifo = dir.path() / "fifo.rbk";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const fs::path& file : {fifo, fs::path("/dev/zero")}) {
    const auto result =
        test::runRockbakeUnder("timeout 20 ", {"resume", file.string(), "-o", (dir.path() / "c").string()});
    EXPECT_EQ(result.exit_status, 2) << file << ": " << result.output;
    EXPECT_NE(result.output.find(file.string() + ": is not a regular file"), std::string::npos) << result.output;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "c"));
}

}  // namespace
}  // namespace rockbake
