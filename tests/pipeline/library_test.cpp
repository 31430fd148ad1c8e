// Libraries (docs/libraries.md): library files, job expansion, manifests, resume,
// interruption, shards, failures, the index and the contact sheet.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <map>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "platform/png_image.h"
#include "core/sha256.h"
#include "pipeline/library_index.h"
#include "pipeline/manifest.h"
#include "preset/library.h"
#include "preset/load_preset.h"
#include "render/contact_sheet.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::readBytes;
using test::runRockbake;
using test::startRockbake;
using test::TempDir;
using test::writeText;

// The shared small preset with renders tiny enough to keep library runs fast.
const std::string kSmallPreset =
    std::string(test::kSmallPreset) + "render: {width: 48, height: 36, quality: 2, antialias: 0}\n";

// The library folder: small.yaml beside lib.yaml.
fs::path writeLibrary(const TempDir& dir, const std::string& library_text) {
  writeText(dir.path() / "small.yaml", kSmallPreset);
  writeText(dir.path() / "lib.yaml", library_text);
  return dir.path() / "lib.yaml";
}

json readJson(const fs::path& file) {
  return json::parse(readBytes(file));
}

std::vector<std::string> jobNames(const std::vector<LibraryJob>& jobs) {
  std::vector<std::string> names;
  for (const auto& job : jobs) names.push_back(job.name);
  return names;
}

std::string libraryError(const TempDir& dir, const std::string& text) {
  writeText(dir.path() / "small.yaml", kSmallPreset);
  try {
    parseLibrary(text, dir.path() / "lib.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// A manifest without what may differ between two bakes of the same inputs: "timings", "host", and the
// stats.json entry of "outputs" (stats.json holds stage seconds).
json comparableManifest(const fs::path& file) {
  json manifest = readJson(file);
  manifest.erase("timings");
  manifest.erase("host");
  json outputs = json::array();
  for (const auto& output : manifest["outputs"])
    if (output["path"] != "stats.json") outputs.push_back(output);
  manifest["outputs"] = outputs;
  return manifest;
}

json comparableIndex(const fs::path& file) {
  json index = readJson(file);
  index.erase("timings");
  index.erase("host");
  return index;
}

// Every manifest in OUT describes its folder truly: each listed output is there with its size and hash.
void expectManifestsTrue(const fs::path& out) {
  for (const auto& entry : fs::directory_iterator(out)) {
    const fs::path manifest_file = entry.path() / kManifestFile;
    if (!fs::is_regular_file(manifest_file)) continue;
    const json manifest = readJson(manifest_file);
    ASSERT_FALSE(manifest["outputs"].empty()) << manifest_file;
    for (const auto& output : manifest["outputs"]) {
      const fs::path file = entry.path() / output["path"].get<std::string>();
      ASSERT_TRUE(fs::is_regular_file(file)) << file << " is listed in " << manifest_file << " but missing";
      EXPECT_EQ(fs::file_size(file), output["size"].get<std::uintmax_t>()) << file;
      EXPECT_EQ(sha256File(file), output["sha256"].get<std::string>()) << file;
    }
  }
}

std::set<std::string> assetFolders(const fs::path& out) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(out))
    if (entry.is_directory()) names.insert(entry.path().filename().string());
  return names;
}

std::int64_t mtimeNs(const fs::path& file) {
  struct stat st {};
  EXPECT_EQ(::stat(file.c_str(), &st), 0) << file;
  return std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
}

// Waits until some folder of `out` holds a manifest (or the process ends); true if one does.
bool waitForFirstManifest(const fs::path& out, ChildProcess& child) {
  for (int i = 0; i < 6000; ++i) {
    std::error_code ec;
    if (fs::is_directory(out, ec))
      for (const auto& entry : fs::directory_iterator(out, ec))
        if (fs::is_regular_file(entry.path() / kManifestFile)) return true;
    if (child.poll()) {
      ADD_FAILURE() << "rockbake ended before any manifest appeared";
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// ---- the library file ----

TEST(LibraryFile, ExpandsPresetsSeedsAndWedgesInOrder) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", kSmallPreset);
  writeText(dir.path() / "sub" / "Big Rock.yaml", kSmallPreset);
  const Library library = parseLibrary(R"(
- preset: small.yaml
  seeds: [5, 2]
  wedges:
    - {name: base}
    - {name: tall, set: {grid.size: [2, 2, 3], time: 0.25}}
- preset: small.yaml
  name: ranged
  seeds: {from: 10, count: 3}
- preset: small.yaml
  name: wedged
  wedges: [{name: soft, set: {colluvium.yield: 0.9}}]
- preset: sub/Big Rock.yaml
)",
                                       dir.path() / "lib.yaml");
  const auto jobs = expandLibrary(library);
  EXPECT_EQ(jobNames(jobs),
            (std::vector<std::string>{"small-base-s5", "small-tall-s5", "small-base-s2", "small-tall-s2", "ranged-s10",
                                      "ranged-s11", "ranged-s12", "wedged-soft", "big-rock"}));
  EXPECT_EQ(jobs[1].seed, 5u);
  EXPECT_FALSE(jobs[7].seed.has_value());  // no seeds: the preset's own
  ASSERT_TRUE(jobs[1].wedge.has_value());
  // Wedge values reach --set form as YAML flow text, in file order, each with where it was written.
  EXPECT_EQ(jobs[1].wedge->sets, (std::vector<std::string>{"grid.size=[2, 2, 3]", "time=0.25"}));
  EXPECT_EQ(jobs[1].wedge->set_origins.front(), (dir.path() / "lib.yaml").string() + ":6:26 (wedge 'tall')");
  EXPECT_TRUE(jobs[0].wedge->sets.empty());
  EXPECT_EQ(library.entries[3].preset_file, dir.path() / "sub" / "Big Rock.yaml");
  EXPECT_EQ(library.sha256.size(), 64u);
}

TEST(LibraryFile, WedgeValuesSurviveTheTripToPresetOverrides) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", kSmallPreset);
  const Library library = parseLibrary(R"(- preset: small.yaml
  wedges:
    - name: styled
      set:
        bake.colluvium_color: '#aa5500'
        export: [ply, glb]
        render: {width: 64, height: 48}
        bubbles.0.bubble: {ellipsoid: {radii: [0.3, 0.3, 0.2]}}
)",
                                       dir.path() / "lib.yaml");
  const auto jobs = expandLibrary(library);
  ASSERT_EQ(jobs.size(), 1u);
  PresetOverrides overrides;
  overrides.sets = jobs[0].wedge->sets;
  const Preset preset = loadPreset(library.entries[0].preset_file, overrides);
  ASSERT_TRUE(preset.bake.colluvium_color.has_value());
  EXPECT_NEAR((*preset.bake.colluvium_color)[0], 0xaa / 255.0, 1e-9);
  EXPECT_EQ(preset.exports, (std::vector<std::string>{"ply", "glb"}));
  EXPECT_EQ(preset.render.width, 64);
  EXPECT_EQ(preset.bubbles[0].bubble.kind, BubbleSpec::Kind::Ellipsoid);
  EXPECT_NE(
      libraryError(dir, "- preset: small.yaml\n  wedges: [{name: a, set: {time=1: 2}}]\n").find("is not a key path"),
      std::string::npos);
}

TEST(LibraryFile, ErrorsNameLineColumnAndKeyPath) {
  TempDir dir;
  const std::string seeds = libraryError(dir, "- preset: small.yaml\n  seds: [1, 2]\n");
  EXPECT_NE(seeds.find("lib.yaml:2:3: 0.seds: unknown key 'seds'; did you mean 'seeds'?"), std::string::npos) << seeds;
  const std::string wedge = libraryError(dir, "- preset: small.yaml\n  wedges:\n    - {name: a, sett: {time: 1}}\n");
  EXPECT_NE(wedge.find("lib.yaml:3:17: 0.wedges.0.sett: unknown key 'sett'; did you mean 'set'?"), std::string::npos)
      << wedge;
  EXPECT_NE(libraryError(dir, "- preset: missing.yaml\n").find("lib.yaml:1:11: 0.preset: no preset file"),
            std::string::npos);
  // A name longer than the file system allows is no file either, not a crash.
  EXPECT_NE(libraryError(dir, "- preset: " + std::string(300, 'r') + ".yaml\n")
                .find("lib.yaml:1:11: 0.preset: no preset file"),
            std::string::npos);
  EXPECT_NE(libraryError(dir, "- preset: small.yaml\n  seeds: {from: 1}\n").find("needs both 'from' and 'count'"),
            std::string::npos);
  EXPECT_NE(libraryError(dir, "- preset: small.yaml\n  seeds: [1, -2]\n").find("0.seeds.1: expected a whole number"),
            std::string::npos);
  EXPECT_NE(libraryError(dir, "- preset: small.yaml\n  wedges: [{name: Tall}]\n").find("may only use a-z"),
            std::string::npos);
  EXPECT_NE(libraryError(dir, "preset: small.yaml\n").find("must be a non-empty YAML list"), std::string::npos);
  // Two entries making one job name would share a folder.
  const std::string clash =
      libraryError(dir, "- preset: small.yaml\n  seeds: [1]\n- preset: small.yaml\n  seeds: [1, 2]\n");
  EXPECT_NE(clash.find("lib.yaml:3:3: 1: job 'small-s1' is also made by entry 0"), std::string::npos) << clash;
}

TEST(LibraryFile, TheShippedLibraryIsValid) {
  const fs::path file = test::sourceDir() / "presets" / "libraries" / "showcase.yaml";
  const auto jobs = expandLibrary(loadLibrary(file));
  EXPECT_EQ(jobNames(jobs),
            (std::vector<std::string>{"goblin-base-s7", "goblin-weathered-s7", "goblin-base-s8", "goblin-weathered-s8",
                                      "hoodoo-cap-s21", "hoodoo-cap-s22", "corner-cavern-base", "corner-cavern-deep"}));
  // Every job's preset loads with its overrides.
  const Library library = loadLibrary(file);
  for (const auto& job : jobs) {
    PresetOverrides overrides;
    if (job.wedge) overrides.sets = job.wedge->sets;
    overrides.seed = job.seed;
    EXPECT_NO_THROW(loadPreset(library.entries[job.entry].preset_file, overrides)) << job.name;
  }
}

TEST(LibraryFile, ShardsSplitTheJobsRoundRobin) {
  std::vector<LibraryJob> jobs(10);
  for (std::size_t i = 0; i < jobs.size(); ++i) jobs[i].name = "job" + std::to_string(i);
  std::multiset<std::string> union_of_shards;
  for (int i = 0; i < 3; ++i)
    for (const auto& job : selectShard(jobs, parseShard(std::to_string(i) + "/3"))) union_of_shards.insert(job.name);
  EXPECT_EQ(union_of_shards.size(), jobs.size());
  for (const auto& job : jobs) EXPECT_EQ(union_of_shards.count(job.name), 1u) << job.name;
  EXPECT_EQ(jobNames(selectShard(jobs, parseShard("1/4"))), (std::vector<std::string>{"job1", "job5", "job9"}));
  for (const char* bad : {"3/3", "1", "a/2", "1/0", "-1/2", "/2"}) EXPECT_THROW(parseShard(bad), InputError) << bad;
}

// ---- the contact sheet ----

TEST(ContactSheet, HasOneLabelledTilePerAsset) {
  TempDir dir;
  RgbImage render{96, 72, std::vector<std::uint8_t>(96 * 72 * 3, 200)};
  writePngRgb(dir.path() / "a.png", render);
  const std::vector<ContactSheetItem> seven = {{"alpha", dir.path() / "a.png", ""},
                                               {"beta", {}, "failed"},
                                               {"c", {}, ""},
                                               {"d", {}, ""},
                                               {"e", {}, ""},
                                               {"f", {}, ""},
                                               {"g", {}, ""}};
  const RgbImage sheet = makeContactSheet(seven);
  EXPECT_EQ(sheet.width, 6 * kThumbWidth + 7 * kGap);
  EXPECT_EQ(sheet.height, 2 * (kThumbHeight + kLabelHeight) + 3 * kGap);
  // The render fills its tile (96×72 scales to 192×144? no: never enlarged, so it sits centred).
  const auto pixel = [&](const RgbImage& image, int x, int y) {
    return image.pixels[(std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3];
  };
  EXPECT_EQ(pixel(sheet, kGap + kThumbWidth / 2, kGap + kThumbHeight / 2), 200);

  // Names are drawn: changing one name changes only pixels in that tile's label and placeholder.
  std::vector<ContactSheetItem> renamed = seven;
  renamed[1].name = "gamma";
  const RgbImage other = makeContactSheet(renamed);
  int changed = 0;
  for (int y = 0; y < sheet.height; ++y)
    for (int x = 0; x < sheet.width; ++x)
      if (pixel(sheet, x, y) != pixel(other, x, y)) {
        ++changed;
        EXPECT_GE(x, kGap + kThumbWidth + kGap);
        EXPECT_LT(x, 2 * (kGap + kThumbWidth));
        EXPECT_LT(y, kGap + kThumbHeight + kLabelHeight);
      }
  EXPECT_GT(changed, 50);
  // Deterministic: the same items, the same pixels.
  EXPECT_EQ(makeContactSheet(seven).pixels, sheet.pixels);
}

TEST(ContactSheet, FitImageKeepsTheAspectAndAverages) {
  RgbImage checker{4, 2, {}};
  for (int i = 0; i < 8; ++i) checker.pixels.insert(checker.pixels.end(), 3, std::uint8_t(i % 2 ? 255 : 0));
  const RgbImage half = fitImage(checker, 2, 2);
  EXPECT_EQ(half.width, 2);
  EXPECT_EQ(half.height, 1);
  for (auto v : half.pixels) EXPECT_EQ(v, 128);
}

// ---- bakes ----

TEST(Library, BakesEveryJobWithManifestIndexAndContactSheet) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, R"(- preset: small.yaml
  seeds: [1, 2]
  wedges:
    - {name: base}
    - {name: long, set: {time: 1.0, grid.resolution: 28}}
)");
  const fs::path out = dir.path() / "out";
  const auto result = runRockbake({"library", lib.string(), "-o", out.string(), "--no-render", "--jobs", "2"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const std::vector<std::string> names = {"small-base-s1", "small-base-s2", "small-long-s1", "small-long-s2"};
  EXPECT_EQ(assetFolders(out), std::set<std::string>(names.begin(), names.end()));
  expectManifestsTrue(out);

  const json base = readJson(out / "small-base-s1" / kManifestFile);
  const json wedged = readJson(out / "small-long-s1" / kManifestFile);
  // The wedge's overrides reach the simulation: longer time, finer grid → more cycles.
  EXPECT_EQ(base["inputs"]["preset"]["grid"]["resolution"], 24);
  EXPECT_EQ(wedged["inputs"]["preset"]["grid"]["resolution"], 28);
  EXPECT_EQ(base["stats"]["cycles"], 6);
  EXPECT_EQ(wedged["stats"]["cycles"], 14);  // h = 2 / 28, time 1 → 14 cycles
  EXPECT_EQ(readJson(out / "small-long-s1" / "stats.json")["cycles"].size(), 14u);
  EXPECT_EQ(wedged["inputs"]["job"]["wedge"], "long");
  EXPECT_EQ(wedged["inputs"]["job"]["set"], json({"time=1.0", "grid.resolution=28"}));
  EXPECT_EQ(wedged["inputs"]["seed"], 1);
  EXPECT_EQ(wedged["inputs"]["preset"]["seed"], 1);
  EXPECT_EQ(wedged["inputs"]["preset"]["name"], "small-long-s1");
  EXPECT_EQ(wedged["inputs"]["library"]["file"], "lib.yaml");
  EXPECT_EQ(wedged["inputs"]["library"]["sha256"], sha256File(lib));
  EXPECT_EQ(wedged["inputs"]["baker_version"], ROCKBAKE_VERSION);
  EXPECT_EQ(wedged["inputs"]["options"], json({{"mesh", true}, {"render", false}}));
  EXPECT_GT(base["stats"]["rock_voxels_initial"].get<int>(), base["stats"]["rock_voxels_final"].get<int>());
  EXPECT_TRUE(base["timings"].contains("stages"));
  EXPECT_TRUE(base.contains("host"));
  std::set<std::string> outputs;
  for (const auto& o : base["outputs"]) outputs.insert(o["path"].get<std::string>());
  for (const char* file : {"rock.vdb", "stats.json", "rock.ply", "rock.glb"}) EXPECT_TRUE(outputs.count(file)) << file;
  EXPECT_FALSE(outputs.count(kManifestFile));

  const json index = readJson(out / "index.json");
  ASSERT_EQ(index["assets"].size(), 4u);
  for (std::size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(index["assets"][i]["name"], names[i]);  // sorted by name
    EXPECT_EQ(index["assets"][i]["status"], "ok");
    EXPECT_EQ(index["assets"][i]["manifest"], names[i] + "/manifest.json");
  }
  EXPECT_EQ(index["counts"]["ok"], 4);
  EXPECT_EQ(index["libraries"][0]["file"], "lib.yaml");

  RgbImage sheet = readPngRgb(out / "contact_sheet.png");
  EXPECT_EQ(sheet.width, 4 * kThumbWidth + 5 * kGap);
  EXPECT_EQ(sheet.height, kThumbHeight + kLabelHeight + 2 * kGap);
}

TEST(Library, RendersReachTheContactSheet) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, "- preset: small.yaml\n  seeds: [1]\n");
  const fs::path out = dir.path() / "out";
  const auto result = runRockbake({"library", lib.string(), "-o", out.string(), "--set", "export=[ply]"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const json index = readJson(out / "index.json");
  ASSERT_EQ(index["assets"].size(), 1u);
  EXPECT_EQ(index["assets"][0]["render"], "small-s1/render.png");
  // The tile holds the downscaled render (48×36, centred, never enlarged), not the grey placeholder.
  const RgbImage render = readPngRgb(out / "small-s1" / "render.png");
  const RgbImage sheet = readPngRgb(out / "contact_sheet.png");
  const int x0 = kGap + (kThumbWidth - render.width) / 2, y0 = kGap + (kThumbHeight - render.height) / 2;
  for (int y = 0; y < render.height; ++y)
    for (int x = 0; x < render.width; ++x)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(sheet.pixels[(std::size_t(y0 + y) * sheet.width + std::size_t(x0 + x)) * 3 + k],
                  render.pixels[(std::size_t(y) * render.width + std::size_t(x)) * 3 + k]);
}

TEST(Library, BadLibraryExitsTwoAndWritesNothing) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, "- preset: small.yaml\n  wedges:\n    - {nme: tall}\n");
  const fs::path out = dir.path() / "out";
  const auto result = runRockbake({"library", lib.string(), "-o", out.string(), "--no-mesh"});
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("lib.yaml:3:8: 0.wedges.0.nme: unknown key 'nme'; did you mean 'name'?"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(out));
  // Bad arguments too.
  writeText(lib, "- preset: small.yaml\n");
  EXPECT_EQ(runRockbake({"library", lib.string(), "-o", out.string(), "--shard", "3/3"}).exit_status, 2);
  EXPECT_EQ(runRockbake({"library", lib.string(), "-o", out.string(), "--jobs", "0"}).exit_status, 2);
  EXPECT_EQ(runRockbake({"library", "-o", out.string()}).exit_status, 2);
  EXPECT_FALSE(fs::exists(out));
}

TEST(Library, ReRunBakesOnlyWhatIsMissing) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, "- preset: small.yaml\n  seeds: {from: 1, count: 3}\n");
  const fs::path out = dir.path() / "out";
  const std::vector<std::string> args = {"library", lib.string(), "-o", out.string(), "--no-mesh"};
  ASSERT_EQ(runRockbake(args).exit_status, 0);
  std::map<std::string, std::int64_t> before;
  for (const char* name : {"small-s1", "small-s2", "small-s3"}) before[name] = mtimeNs(out / name / "rock.vdb");
  const std::string vdb = readBytes(out / "small-s2" / "rock.vdb");
  // A manifest cut off (a disk that filled up, say) is not a complete asset: the folder is baked again.
  const std::string manifest = readBytes(out / "small-s2" / kManifestFile);
  writeText(out / "small-s2" / kManifestFile, manifest.substr(0, manifest.size() / 2));

  const auto again = runRockbake(args);
  ASSERT_EQ(again.exit_status, 0) << again.output;
  const json index = readJson(out / "index.json");
  EXPECT_EQ(index["assets"][0]["status"], "skipped-resumed");
  EXPECT_EQ(index["assets"][1]["status"], "ok");
  EXPECT_EQ(index["assets"][2]["status"], "skipped-resumed");
  EXPECT_EQ(index["timings"]["this_run"]["small-s2"], "baked");
  EXPECT_EQ(mtimeNs(out / "small-s1" / "rock.vdb"), before["small-s1"]);
  EXPECT_EQ(mtimeNs(out / "small-s3" / "rock.vdb"), before["small-s3"]);
  EXPECT_NE(mtimeNs(out / "small-s2" / "rock.vdb"), before["small-s2"]);
  EXPECT_EQ(readBytes(out / "small-s2" / "rock.vdb"), vdb);
  expectManifestsTrue(out);

  // An input that changes the outputs (here --set) makes every job bake again.
  const auto changed = runRockbake({"library", lib.string(), "-o", out.string(), "--no-mesh", "--set", "time=0.25"});
  ASSERT_EQ(changed.exit_status, 0) << changed.output;
  const auto rebaked_index = readJson(out / "index.json");  // a named value: a range-for keeps no temporary alive
  for (const auto& asset : rebaked_index["assets"]) EXPECT_EQ(asset["status"], "ok");
  EXPECT_EQ(readJson(out / "small-s1" / kManifestFile)["stats"]["cycles"], 3);
}

TEST(Library, KilledRunResumesToTheSameOutputs) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, "- preset: small.yaml\n  seeds: {from: 1, count: 8}\n");
  const fs::path reference = dir.path() / "reference", out = dir.path() / "out";
  const std::vector<std::string> options = {"--no-render", "--set", "grid.resolution=32", "--jobs", "1"};
  std::vector<std::string> args = {"library", lib.string(), "-o", reference.string()};
  args.insert(args.end(), options.begin(), options.end());
  ASSERT_EQ(runRockbake(args).exit_status, 0);

  args[3] = out.string();
  const auto child = startRockbake(args, dir.path() / "killed.log");
  ASSERT_GT(child->pid(), 0);
  const bool started = waitForFirstManifest(out, *child);
  ::kill(child->pid(), SIGKILL);
  child->wait();
  ASSERT_TRUE(started);
  // Whatever the kill left: no folder has a manifest that promises more than is there.
  expectManifestsTrue(out);

  const auto resumed = runRockbake(args);
  ASSERT_EQ(resumed.exit_status, 0) << resumed.output;
  EXPECT_EQ(assetFolders(out), assetFolders(reference));
  for (const auto& name : assetFolders(reference)) {
    EXPECT_EQ(readBytes(out / name / "rock.vdb"), readBytes(reference / name / "rock.vdb")) << name;
    EXPECT_EQ(readBytes(out / name / "rock.glb"), readBytes(reference / name / "rock.glb")) << name;
    EXPECT_EQ(comparableManifest(out / name / kManifestFile), comparableManifest(reference / name / kManifestFile))
        << name;
  }
  expectManifestsTrue(out);
  EXPECT_EQ(readJson(out / "index.json")["counts"]["ok"].get<int>() +
                readJson(out / "index.json")["counts"]["skipped-resumed"].get<int>(),
            8);
}

TEST(Library, InterruptStopsCleanlyWithStatus130) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, "- preset: small.yaml\n  seeds: {from: 1, count: 12}\n");
  const fs::path out = dir.path() / "out";
  const auto child = startRockbake(
      {"library", lib.string(), "-o", out.string(), "--no-mesh", "--set", "grid.resolution=40", "--jobs", "1"},
      dir.path() / "interrupted.log");
  ASSERT_GT(child->pid(), 0);
  ASSERT_TRUE(waitForFirstManifest(out, *child));
  ::kill(child->pid(), SIGINT);
  const int status = child->wait();
  ASSERT_TRUE(WIFEXITED(status)) << readBytes(dir.path() / "interrupted.log");
  EXPECT_EQ(WEXITSTATUS(status), 130) << readBytes(dir.path() / "interrupted.log");
  // The index lists what finished; the rest has no manifest.
  const json index = readJson(out / "index.json");
  EXPECT_GE(index["assets"].size(), 1u);
  EXPECT_LT(index["assets"].size(), 12u);
  EXPECT_TRUE(index["timings"]["cancelled"].get<bool>());
  for (const auto& asset : index["assets"]) EXPECT_EQ(asset["status"], "ok");
  expectManifestsTrue(out);
}

// Ctrl-C during a render: POV-Ray is killed rather than left to finish, and the job leaves no render and no
// manifest behind.
TEST(Library, InterruptKillsARunningRender) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, "- preset: small.yaml\n  seeds: [1]\n");
  const fs::path out = dir.path() / "out";
  // A render slow enough (seconds) to be interrupted in the middle.
  const auto child =
      startRockbake({"library", lib.string(), "-o", out.string(), "--set", "render.width=1600", "--set",
                     "render.height=1200", "--set", "render.quality=9", "--set", "render.antialias=0.02"},
                    dir.path() / "interrupted.log");
  ASSERT_GT(child->pid(), 0);
  // scene.pov is written just before POV-Ray starts.
  bool rendering = false;
  for (int i = 0; i < 6000 && !rendering; ++i) {
    // In the hidden folder the bake writes before it is renamed into place.
    std::error_code ec;
    if (fs::is_directory(out, ec))
      for (const auto& entry : fs::directory_iterator(out, ec))
        rendering = rendering || fs::is_regular_file(entry.path() / "scene.pov");
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(rendering) << readBytes(dir.path() / "interrupted.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(child->pid(), SIGINT);
  const int status = child->wait();
  const std::string log = readBytes(dir.path() / "interrupted.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 130) << log;
  EXPECT_FALSE(fs::exists(out / "small-s1" / "render.exr")) << "the render ran to its end:\n" << log;
  EXPECT_FALSE(fs::exists(out / "small-s1" / kManifestFile));
  EXPECT_EQ(readJson(out / "index.json")["assets"].size(), 0u);
}

TEST(Library, ShardsTogetherEqualOneRunAndIndexOnlyMergesThem) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, R"(- preset: small.yaml
  seeds: [1, 2]
  wedges: [{name: a}, {name: b, set: {colluvium.yield: 0.9}}]
- preset: small.yaml
  name: other
  seeds: [7]
)");
  const fs::path single = dir.path() / "single", sharded = dir.path() / "sharded";
  ASSERT_EQ(runRockbake({"library", lib.string(), "-o", single.string(), "--no-render", "--jobs", "1"}).exit_status, 0);
  std::multiset<std::string> baked;
  for (int i = 0; i < 3; ++i) {
    const auto shard = runRockbake({"library", lib.string(), "-o", sharded.string(), "--no-render", "--shard",
                                    std::to_string(i) + "/3", "--jobs", "2", "--threads", "2"});
    ASSERT_EQ(shard.exit_status, 0) << shard.output;
    const json index = readJson(sharded / "index.json");
    for (const auto& [name, status] : index["timings"]["this_run"].items()) {
      EXPECT_EQ(status, "baked") << name;
      baked.insert(name);
    }
  }
  // Every job exactly once, and the last shard's index is the whole library's.
  EXPECT_EQ(baked, std::multiset<std::string>({"other-s7", "small-a-s1", "small-a-s2", "small-b-s1", "small-b-s2"}));
  EXPECT_EQ(comparableIndex(sharded / "index.json"), comparableIndex(single / "index.json"));
  for (const auto& name : assetFolders(single)) {
    EXPECT_EQ(readBytes(sharded / name / "rock.vdb"), readBytes(single / name / "rock.vdb")) << name;
    EXPECT_EQ(readBytes(sharded / name / "rock.ply"), readBytes(single / name / "rock.ply")) << name;
    EXPECT_EQ(comparableManifest(sharded / name / kManifestFile), comparableManifest(single / name / kManifestFile));
  }

  fs::remove(sharded / "index.json");
  fs::remove(sharded / "contact_sheet.png");
  const auto merged = runRockbake({"library", "--index-only", sharded.string()});
  ASSERT_EQ(merged.exit_status, 0) << merged.output;
  EXPECT_EQ(comparableIndex(sharded / "index.json"), comparableIndex(single / "index.json"));
  EXPECT_EQ(readBytes(sharded / "contact_sheet.png"), readBytes(single / "contact_sheet.png"));
}

TEST(Library, FailedJobIsRecordedWhileTheOthersBake) {
  TempDir dir;
  const fs::path lib = writeLibrary(dir, R"(- preset: small.yaml
  seeds: [1]
  wedges:
    - {name: good}
    - {name: bad, set: {colluvium.yield: 2.5}}
)");
  const fs::path out = dir.path() / "out";
  const auto result = runRockbake({"library", lib.string(), "-o", out.string(), "--no-mesh"});
  EXPECT_EQ(result.exit_status, 1) << result.output;
  EXPECT_NE(result.output.find("small-bad-s1"), std::string::npos) << result.output;
  const json index = readJson(out / "index.json");
  ASSERT_EQ(index["assets"].size(), 2u);
  EXPECT_EQ(index["assets"][0]["name"], "small-bad-s1");
  EXPECT_EQ(index["assets"][0]["status"], "failed");
  const std::string message = index["assets"][0]["message"];
  EXPECT_NE(message.find("colluvium.yield: must be in [0, 1], found 2.5"), std::string::npos) << message;
  EXPECT_EQ(index["assets"][0]["job"]["wedge"], "bad");
  EXPECT_EQ(index["assets"][1]["status"], "ok");
  EXPECT_FALSE(fs::exists(out / "small-bad-s1" / kManifestFile));
  EXPECT_TRUE(fs::exists(out / "small-good-s1" / kManifestFile));
  EXPECT_EQ(index["counts"]["failed"], 1);

  // Fixed, the failed job bakes on the next run and the good one is left alone.
  writeText(lib,
            "- preset: small.yaml\n  seeds: [1]\n  wedges:\n    - {name: good}\n"
            "    - {name: bad, set: {colluvium.yield: 0.25}}\n");
  const auto fixed = runRockbake({"library", lib.string(), "-o", out.string(), "--no-mesh"});
  EXPECT_EQ(fixed.exit_status, 0) << fixed.output;
  const json again = readJson(out / "index.json");
  EXPECT_EQ(again["assets"][0]["status"], "ok");
  EXPECT_EQ(again["assets"][1]["status"], "skipped-resumed");
  EXPECT_FALSE(fs::exists(out / "small-bad-s1" / kFailureFile));
}

TEST(LibraryIndex, ListsAssetsWithNumbersInNaturalOrder) {
  TempDir dir;
  // Failed jobs' folders (a failure.json is all they need to be listed); their order is the point here.
  for (const char* name : {"talus-s10", "talus-s9", "arch-s2", "talus-s011", "talus-s1"})
    writeText(dir.path() / name / "failure.json", R"({"message": "a bad preset"})");
  writeLibraryIndex(dir.path(), {}, nlohmann::ordered_json::object());
  const json index = json::parse(readBytes(dir.path() / "index.json"));
  std::vector<std::string> names;
  for (const auto& asset : index.at("assets")) names.push_back(asset.at("name").get<std::string>());
  EXPECT_EQ(names, (std::vector<std::string>{"arch-s2", "talus-s1", "talus-s9", "talus-s10", "talus-s011"}));
}

TEST(Manifest, BakeWritesItLastListingWhatItWrote) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", kSmallPreset);
  const fs::path out = dir.path() / "out";
  // A file left from before in the asset folder (an earlier bake's) is not this bake's output.
  ASSERT_EQ(runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-mesh"}).exit_status,
            0);
  writeText(out / "small" / "notes.txt", "mine");
  const auto result = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-render",
                                   "--set", "export=[ply]", "--seed", "9"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const json manifest = readJson(out / "small" / kManifestFile);
  std::set<std::string> outputs;
  for (const auto& o : manifest["outputs"]) outputs.insert(o["path"].get<std::string>());
  // export=[ply]: no rock.vdb either; asset.json describes the meshes.
  EXPECT_EQ(outputs, (std::set<std::string>{"asset.json", "colluvium.ply", "rock.ply", "stats.json"}));
  expectManifestsTrue(out);
  EXPECT_EQ(manifest["asset"], "small");
  EXPECT_EQ(manifest["inputs"]["seed"], 9);
  EXPECT_EQ(manifest["inputs"]["job"]["seed"], 9);
  EXPECT_EQ(manifest["inputs"]["job"]["preset"], "small.yaml");
  EXPECT_EQ(manifest["inputs"]["job"]["set"], json({"export=[ply]"}));
  EXPECT_TRUE(manifest["inputs"]["library"].is_null());
  // The manifest is the newest file of the folder.
  const auto manifest_time = fs::last_write_time(out / "small" / kManifestFile);
  for (const auto& file : outputs) EXPECT_LE(fs::last_write_time(out / "small" / file), manifest_time) << file;
}

// In a library, a warning says which job it is of: jobs bake side by side and their logs interleave.
TEST(LibraryRun, WarningsNameTheirJob) {
  TempDir dir;
  std::string wide = kSmallPreset;
  const std::string box = "box: {size: [1.5, 1.5, 1.5]}";
  wide.replace(wide.find(box), box.size(), "box: {size: [2.6, 1.5, 1.5]}");  // wider than grid.size
  writeText(dir.path() / "wide.yaml", wide);
  writeText(dir.path() / "lib.yaml", "- preset: wide.yaml\n  seeds: [1, 2]\n");
  const auto result = runRockbake({"library", (dir.path() / "lib.yaml").string(), "-o", (dir.path() / "out").string(),
                                   "--no-render", "--jobs", "2"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  for (const char* job : {"wide-s1", "wide-s2"})
    EXPECT_NE(result.output.find(std::string(job) + ": the shape reaches beyond grid.size and was clipped to it"),
              std::string::npos)
        << job << "\n"
        << result.output;
}

// `rockbake review` on a folder of plain bakes (no library, no index.json) indexes it first, as
// `library --index-only` does, and serves it; an empty folder is refused, saying what to bake.
TEST(Review, APlainBakesFolderIsIndexedAndServed) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", kSmallPreset);
  const fs::path out = dir.path() / "out";
  ASSERT_EQ(runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-render"}).exit_status,
            0);
  ASSERT_FALSE(fs::exists(out / "index.json"));
  const auto served = test::runRockbakeUnder("timeout -s INT 4 ", {"review", out.string(), "--port", "0"});
  EXPECT_NE(served.output.find("review: indexed"), std::string::npos) << served.output;
  EXPECT_NE(served.output.find("review: http://127.0.0.1:"), std::string::npos) << served.output;
  const json index = readJson(out / "index.json");
  ASSERT_EQ(index["assets"].size(), 1u) << index.dump();
  EXPECT_EQ(index["assets"][0]["name"], "small");
  fs::create_directories(dir.path() / "empty");
  const auto empty = runRockbake({"review", (dir.path() / "empty").string(), "--port", "0"});
  EXPECT_EQ(empty.exit_status, 2) << empty.output;
  EXPECT_NE(empty.output.find("rockbake bake PRESET -o"), std::string::npos) << empty.output;
}

// `rockbake render` writes new renders into a finished folder: its manifest follows them, so the folder
// still reads as complete (a library re-run does not bake it again).
TEST(Manifest, RerenderUpdatesTheRenderOutputs) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", kSmallPreset);
  const fs::path out = dir.path() / "out";
  ASSERT_EQ(runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--set", "export=[glb]"})
                .exit_status,
            0);
  const std::string render_sha = sha256File(out / "small" / "render.exr");
  const auto result = runRockbake({"render", (out / "small").string(), "--template", "debug", "--output", "render"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  ASSERT_NE(sha256File(out / "small" / "render.exr"), render_sha) << "the debug template renders differently";
  expectManifestsTrue(out);
  json manifest = readJson(out / "small" / kManifestFile);
  EXPECT_EQ(manifest["rerender"]["template"], "debug");
  std::set<std::string> outputs;
  for (const auto& o : manifest["outputs"]) outputs.insert(o["path"].get<std::string>());
  EXPECT_TRUE(outputs.count("render.exr") && outputs.count("rock.glb") && outputs.count("scene.pov"));
  // A still of another name joins the outputs.
  ASSERT_EQ(runRockbake({"render", (out / "small").string(), "--template", "debug"}).exit_status, 0);
  expectManifestsTrue(out);
  manifest = readJson(out / "small" / kManifestFile);
  EXPECT_EQ(manifest["rerender"]["still"], "render_debug");
  outputs.clear();
  for (const auto& o : manifest["outputs"]) outputs.insert(o["path"].get<std::string>());
  EXPECT_TRUE(outputs.count("render_debug.exr") && outputs.count("render_debug.png") &&
              outputs.count("render_debug.pov"));
}

}  // namespace
}  // namespace rockbake
