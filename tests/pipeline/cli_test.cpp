// The command line end to end, with the real executable (docs/command-line.md).
#include <gtest/gtest.h>

#include <cstdlib>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using test::kSmallPreset;
using test::readBytes;
using test::runRockbake;
using test::TempDir;
using test::writeText;

std::string presetPath(const std::string& name) {
  return (test::sourceDir() / "presets" / name).string();
}

TEST(Cli, VersionAndHelpExitZero) {
  const auto version = runRockbake({"--version"});
  EXPECT_EQ(version.exit_status, 0);
  EXPECT_NE(version.output.find("rockbake "), std::string::npos);
  const auto help = runRockbake({"bake", "--help"});
  EXPECT_EQ(help.exit_status, 0);
  for (const char* flag :
       {"--threads", "--seed", "--set", "--resolution", "--no-mesh", "--no-render", "--no-textures", "--out"})
    EXPECT_NE(help.output.find(flag), std::string::npos) << flag;
}

TEST(Cli, BadArgumentsExitTwo) {
  EXPECT_EQ(runRockbake({}).exit_status, 2);
  EXPECT_EQ(runRockbake({"bake"}).exit_status, 2);
  EXPECT_EQ(runRockbake({"bake", "/nonexistent/preset.yaml"}).exit_status, 2);
  EXPECT_EQ(runRockbake({"bake", presetPath("goblin.yaml"), "--threads", "0"}).exit_status, 2);
  EXPECT_EQ(runRockbake({"bake", presetPath("goblin.yaml"), "--frobnicate"}).exit_status, 2);
}

// -v / --verbose is the tool's, and is taken before or after the subcommand (docs/command-line.md).
TEST(Cli, VerboseIsTakenBeforeOrAfterTheSubcommand) {
  TempDir dir;
  const auto bake = [&](std::vector<std::string> args, const char* out) {
    std::vector<std::string> all{"bake",        presetPath("goblin.yaml"), "--resolution", "24",
                                 "--no-render", "--no-textures",           "-o",           (dir.path() / out).string()};
    all.insert(all.end(), args.begin(), args.end());
    return runRockbake(all);
  };
  const auto quiet = bake({}, "quiet"), after = bake({"-v"}, "after"), long_after = bake({"--verbose"}, "long");
  const auto before = runRockbake({"-v", "bake", presetPath("goblin.yaml"), "--resolution", "24", "--no-render",
                                   "--no-textures", "-o", (dir.path() / "before").string()});
  for (const auto* r : {&quiet, &after, &long_after, &before}) ASSERT_EQ(r->exit_status, 0) << r->output;
  EXPECT_EQ(quiet.output.find("debug:"), std::string::npos) << quiet.output;
  for (const auto* r : {&after, &long_after, &before}) EXPECT_NE(r->output.find("debug:"), std::string::npos);
}

TEST(Cli, BakeWritesTheVdbAndStats) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", kSmallPreset);
  const auto out = dir.path() / "out";
  const auto result = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-mesh"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  EXPECT_TRUE(fs::is_regular_file(out / "small" / "rock.vdb"));
  const auto stats = nlohmann::json::parse(readBytes(out / "small" / "stats.json"));
  // h = 2 / 24, time 0.5 → ceil(6) = 6 cycles.
  ASSERT_EQ(stats["cycles"].size(), 6u);
  std::size_t previous_rock = std::size_t(-1);
  for (const auto& c : stats["cycles"]) {
    for (const char* key : {"cycle", "time", "rock", "exposed", "decimated", "colluvium", "fallen", "removed"})
      EXPECT_TRUE(c.contains(key)) << key;
    EXPECT_LE(c["rock"].get<std::size_t>(), previous_rock);
    previous_rock = c["rock"].get<std::size_t>();
  }
  EXPECT_NEAR(stats["cycles"].back()["time"].get<double>(), 0.5, 1e-9);
  for (const char* stage : {"load", "shape", "simulate"}) EXPECT_GE(stats["stages"][stage].get<double>(), 0.0);
  EXPECT_EQ(stats["preset"]["name"], "small");
  EXPECT_EQ(stats["preset"]["grid"]["resolution"], 24);
  // Nothing but the outputs and the manifest: no temporary files left behind.
  for (const auto& entry : fs::directory_iterator(out / "small"))
    EXPECT_TRUE(entry.path().filename() == "rock.vdb" || entry.path().filename() == "stats.json" ||
                entry.path().filename() == "manifest.json")
        << entry.path();
}

TEST(Cli, OverridesReachTheSimulation) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", kSmallPreset);
  const auto out = dir.path() / "out";
  const auto result = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--resolution",
                                   "16", "--seed", "99", "--set", "cycles=3", "--set", "bubbles.0.cavernous=0.7"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const auto stats = nlohmann::json::parse(readBytes(out / "small" / "stats.json"));
  EXPECT_EQ(stats["cycles"].size(), 3u);
  EXPECT_EQ(stats["preset"]["grid"]["resolution"], 16);
  EXPECT_EQ(stats["preset"]["seed"], 99);
  EXPECT_EQ(stats["preset"]["bubbles"][0]["cavernous"], 0.7);
}

// docs/model.md §10: same preset and seed → byte-identical outputs at any thread count.
// goblin: noise, two bubble bands, a collection, an image; hoodoo-cap: a cap
// that falls (drop) and colluvium with removal; talus-cliff: crumbling rockfall.
// Their geology: goblin and hoodoo-cap jointed, talus-cliff's dipping beds,
// every one's variation, and tafoni-wall's rind (both through the distance field).
TEST(Cli, RockVdbIsByteIdenticalAcrossThreadCountsAndRuns) {
  for (const char* preset : {"goblin", "hoodoo-cap", "talus-cliff", "tafoni-wall"}) {
    TempDir dir;
    const std::vector<std::string> common = {"bake", presetPath(std::string(preset) + ".yaml"), "--resolution", "48",
                                             "--no-mesh"};
    std::vector<std::string> outputs;
    std::size_t fallen = 0;
    for (const auto& [name, threads] :
         std::vector<std::pair<std::string, std::string>>{{"one", "1"}, {"two", "2"}, {"again", "2"}}) {
      auto args = common;
      args.insert(args.end(), {"-o", (dir.path() / name).string(), "--threads", threads});
      const auto result = runRockbake(args);
      ASSERT_EQ(result.exit_status, 0) << result.output;
      outputs.push_back(readBytes(dir.path() / name / preset / "rock.vdb"));
      const auto stats = nlohmann::json::parse(readBytes(dir.path() / name / preset / "stats.json"));
      for (const auto& c : stats["cycles"]) fallen += c["fallen"].get<std::size_t>();
    }
    ASSERT_GT(outputs[0].size(), 1000u) << preset;
    EXPECT_TRUE(outputs[0] == outputs[1]) << preset << ": 1 vs 2 threads differ";
    EXPECT_TRUE(outputs[1] == outputs[2]) << preset << ": two runs differ";
    if (std::string(preset) == "hoodoo-cap") {
      EXPECT_GT(fallen, 0u) << "the cap should fall";
    }
  }
}

// collision.glb likewise (docs/collision.md): the parts, their merging and Qhull's hulls are the same bytes at
// one thread and two. hoodoo-cap, with its colluvium hulled too (both materials, a fallen cap).
TEST(Cli, CollisionGlbIsByteIdenticalAcrossThreadCountsAndRuns) {
  TempDir dir;
  std::vector<std::string> outputs;
  for (const auto& [name, threads] :
       std::vector<std::pair<std::string, std::string>>{{"one", "1"}, {"two", "2"}, {"again", "2"}}) {
    const auto result = runRockbake({"bake", presetPath("hoodoo-cap.yaml"), "--resolution", "40", "--no-render",
                                     "--set", "export=[collision]", "--set", "collision.colluvium=true", "-o",
                                     (dir.path() / name).string(), "--threads", threads});
    ASSERT_EQ(result.exit_status, 0) << result.output;
    outputs.push_back(readBytes(dir.path() / name / "hoodoo-cap" / "collision.glb"));
  }
  ASSERT_GT(outputs[0].size(), 1000u);
  EXPECT_NE(outputs[0].find("UCX_colluvium_lod0_00"), std::string::npos) << "the colluvium should be hulled";
  EXPECT_TRUE(outputs[0] == outputs[1]) << "1 vs 2 threads differ";
  EXPECT_TRUE(outputs[1] == outputs[2]) << "two runs differ";
}

// ROCKBAKE_ALPHA_PATH forces how bubble counts are made; the counts, and so
// the files, are the same on every path and at any thread count. goblin at 96
// has an ellipsoid whose rows are cut into pieces.
TEST(Cli, RockVdbIsByteIdenticalOnEveryAlphaPath) {
  TempDir dir;
  std::vector<std::string> outputs;
  for (const auto& [path, threads] : std::vector<std::pair<std::string, std::string>>{
           {"portable", "1"}, {"portable", "2"}, {"avx512", "1"}, {"avx512", "2"}, {"auto", "2"}}) {
    // On a CPU without AVX-512 the avx512 runs fall back to portable (with a warning).
    ::setenv("ROCKBAKE_ALPHA_PATH", path.c_str(), 1);
    const std::string out = (dir.path() / (path + threads)).string();
    const auto result = runRockbake(
        {"bake", presetPath("goblin.yaml"), "--resolution", "96", "--no-mesh", "-o", out, "--threads", threads});
    ::unsetenv("ROCKBAKE_ALPHA_PATH");
    ASSERT_EQ(result.exit_status, 0) << result.output;
    outputs.push_back(readBytes(std::filesystem::path(out) / "goblin" / "rock.vdb"));
  }
  ASSERT_GT(outputs[0].size(), 1000u);
  for (std::size_t i = 1; i < outputs.size(); ++i) EXPECT_TRUE(outputs[i] == outputs[0]) << "run " << i << " differs";
}

// docs/model.md §10 with meshes: rock.vdb, LOD0 and the LOD chain byte-identical at 1
// and 2 threads, through one subdivision level (goblin's house detail) and
// through none (grains five voxels wide: LOD0 simplified from the extraction,
// as at a hero resolution; docs/meshes.md).
TEST(Cli, MeshesAreByteIdenticalAcrossThreadCounts) {
  for (const char* period : {"0.08", "0.6"}) {
    TempDir dir;
    std::vector<std::map<std::string, std::string>> outputs;
    for (const char* threads : {"1", "2"}) {
      const std::string out = (dir.path() / threads).string();
      const auto result =
          runRockbake({"-v", "bake", presetPath("goblin.yaml"), "--resolution", "48", "--no-render", "--set",
                       std::string("mesh.detail.period=") + period, "-o", out, "--threads", threads});
      ASSERT_EQ(result.exit_status, 0) << result.output;
      EXPECT_NE(result.output.find(std::string(period) == "0.6" ? "0 subdivision level(s)" : "1 subdivision level(s)"),
                std::string::npos)
          << result.output;
      std::map<std::string, std::string> files;
      for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(out) / "goblin")) {
        const std::string name = entry.path().filename().string();
        if (name.ends_with(".vdb") || name.ends_with(".ply") || name.ends_with(".glb"))
          files[name] = readBytes(entry.path());
      }
      outputs.push_back(std::move(files));
    }
    ASSERT_EQ(outputs[0].size(), 9u) << "rock.vdb, two PLYs, rock.glb, four LODs and collision.glb";
    for (const auto& [name, bytes] : outputs[0]) {
      ASSERT_TRUE(outputs[1].count(name)) << name;
      EXPECT_TRUE(bytes == outputs[1].at(name)) << period << ": " << name << " differs at 1 and 2 threads";
    }
  }
}

// The whole recipe, rendered small: bake writes meshes and a render; `render`
// re-renders the asset folder with another template without re-simulating.
TEST(Cli, BakeRendersAndRenderReRendersTheAssetFolder) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", std::string(kSmallPreset) +
                                           "mesh: {subdivision: 0, lods: []}\nexport: [ply, glb]\n"
                                           "render: {template: studio, width: 64, height: 48, quality: 4}\n");
  const auto out = dir.path() / "out";
  const auto baked = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string()});
  ASSERT_EQ(baked.exit_status, 0) << baked.output;
  for (const char* file : {"rock.ply", "rock.glb", "render.exr", "render.png", "scene.pov"})
    EXPECT_TRUE(fs::is_regular_file(out / "small" / file)) << file;
  EXPECT_FALSE(fs::exists(out / "small" / "rock.obj"));  // not in export:
  EXPECT_FALSE(fs::exists(out / "small" / "rock.vdb"));  // nor this

  // One fingerprint of the preset: the render's header carries the manifest's
  // preset_sha256, and a copy of the preset baked from another folder renders
  // the same bytes.
  const auto manifest = nlohmann::json::parse(readBytes(out / "small" / "manifest.json"));
  const std::string fingerprint = manifest["inputs"]["preset_sha256"].get<std::string>();
  EXPECT_EQ(fingerprint.size(), 64u);
  EXPECT_NE(readBytes(out / "small" / "render.exr").find(fingerprint), std::string::npos);
  fs::create_directories(dir.path() / "elsewhere" / "deeper");
  fs::copy_file(dir.path() / "small.yaml", dir.path() / "elsewhere" / "deeper" / "small.yaml");
  const auto moved = runRockbake({"bake", (dir.path() / "elsewhere" / "deeper" / "small.yaml").string(), "-o",
                                  (dir.path() / "elsewhere" / "out").string()});
  ASSERT_EQ(moved.exit_status, 0) << moved.output;
  EXPECT_EQ(readBytes(dir.path() / "elsewhere" / "out" / "small" / "render.exr"),
            readBytes(out / "small" / "render.exr"));
  const auto stats = nlohmann::json::parse(readBytes(out / "small" / "stats.json"));
  for (const char* stage : {"mesh_extract", "mesh_subdivide", "export", "render"})
    EXPECT_GT(stats["stages"][stage].get<double>(), 0.0) << stage;

  // Another template renders beside the bake's own still, never over it: render_<template> by default,
  // or the name --output gives; a name that is not a file name is refused.
  const std::string still = readBytes(out / "small" / "render.exr");
  const auto again = runRockbake({"render", (out / "small").string(), "--template", "debug"});
  ASSERT_EQ(again.exit_status, 0) << again.output;
  EXPECT_EQ(readBytes(out / "small" / "render.exr"), still) << "the bake's render was replaced";
  EXPECT_NE(readBytes(out / "small" / "render_debug.exr"), still) << "the debug template should render differently";
  EXPECT_TRUE(fs::exists(out / "small" / "render_debug.png"));
  const auto named = runRockbake({"render", (out / "small").string(), "--template", "debug", "--output", "flat"});
  ASSERT_EQ(named.exit_status, 0) << named.output;
  EXPECT_EQ(readBytes(out / "small" / "flat.exr").size(), readBytes(out / "small" / "render_debug.exr").size());
  const auto escape = runRockbake({"render", (out / "small").string(), "--output", "../x"});
  EXPECT_EQ(escape.exit_status, 2) << escape.output;
  EXPECT_FALSE(fs::exists(out / "x.exr"));

  // --no-render stops after the meshes; --no-mesh after the VDB, which it
  // writes whatever export: lists (it is all such a bake gives).
  const auto no_render =
      runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", (dir.path() / "b").string(), "--no-render"});
  ASSERT_EQ(no_render.exit_status, 0) << no_render.output;
  EXPECT_TRUE(fs::exists(dir.path() / "b" / "small" / "rock.ply"));
  EXPECT_FALSE(fs::exists(dir.path() / "b" / "small" / "render.exr"));
  const auto no_mesh =
      runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", (dir.path() / "c").string(), "--no-mesh"});
  ASSERT_EQ(no_mesh.exit_status, 0) << no_mesh.output;
  EXPECT_TRUE(fs::exists(dir.path() / "c" / "small" / "rock.vdb"));
  EXPECT_FALSE(fs::exists(dir.path() / "c" / "small" / "rock.ply"));
  EXPECT_EQ(runRockbake({"render", dir.path().string()}).exit_status, 2);
}

struct BadPreset {
  const char* label;
  std::string yaml;
  std::string expect_location;  // "file:line:col" suffix after the file name
  std::string expect_key;       // key path in the message ("" for syntax errors)
};

TEST(Cli, BadPresetsExitTwoWithLocationAndWriteNothing) {
  const std::vector<BadPreset> cases = {
      {"malformed YAML", "rockbake: 1\nname: bad\ngrid: {size: [1, 2, 3}\n", ":3:", ""},
      {"wrong type", std::string(kSmallPreset) + "colluvium: {yield: lots}\n", ":13:", "colluvium.yield"},
      {"unknown key", std::string(kSmallPreset) + "respnse: {power: 2}\n", ":13:1", "respnse"},
      {"out of range", std::string(kSmallPreset) + "colluvium: {yield: 1.5}\n", ":13:", "colluvium.yield"},
      {"missing PNG", "rockbake: 1\nname: bad\nshape:\n  image: {path: nowhere.png, height: 1.0}\ntime: 1\n",
       ":4:", "shape.image.path"},
  };
  for (const auto& c : cases) {
    TempDir dir;
    const auto preset = dir.path() / "bad.yaml";
    writeText(preset, c.yaml);
    const auto out = dir.path() / "out";
    const auto result = runRockbake({"bake", preset.string(), "-o", out.string()});
    EXPECT_EQ(result.exit_status, 2) << c.label << "\n" << result.output;
    EXPECT_NE(result.output.find(preset.string() + c.expect_location), std::string::npos) << c.label << "\n"
                                                                                          << result.output;
    EXPECT_NE(result.output.find(c.expect_key), std::string::npos) << c.label << "\n" << result.output;
    EXPECT_FALSE(fs::exists(out)) << c.label;
  }
  // The unknown key gets a suggestion.
  TempDir dir;
  writeText(dir.path() / "bad.yaml", std::string(kSmallPreset) + "respnse: {power: 2}\n");
  const auto result = runRockbake({"bake", (dir.path() / "bad.yaml").string(), "-o", (dir.path() / "out").string()});
  EXPECT_NE(result.output.find("did you mean 'response'"), std::string::npos) << result.output;
}

TEST(Cli, ABadPresetAmongGoodOnesBakesNothing) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", kSmallPreset);
  writeText(dir.path() / "bad.yaml", std::string(kSmallPreset) + "extra_key: 1\n");
  const auto out = dir.path() / "out";
  const auto result = runRockbake(
      {"bake", (dir.path() / "small.yaml").string(), (dir.path() / "bad.yaml").string(), "-o", out.string()});
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_FALSE(fs::exists(out));
}

// Every phase after the simulation says when it starts, and the texture set each LOD's maps: a
// default bake is never silent for seconds.
TEST(Cli, EveryPhaseOfABakeIsLogged) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", std::string(kSmallPreset) + "texture: {size: 256}\n");
  const auto result = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", (dir.path() / "out").string()});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  std::size_t at = 0;
  for (const char* phase :
       {"small: meshes and collision hulls (", "small: the texture set (", "small: texture set: 1 LOD unwrapped (",
        "small: texture set: LOD0's maps, 256 × 256 (1 of 1, ", "small: writing the meshes", "small: rendering ("}) {
    const std::size_t found = result.output.find(phase, at);
    EXPECT_NE(found, std::string::npos) << phase << " (in order)\n" << result.output;
    if (found != std::string::npos) at = found;
  }
}

TEST(Cli, EveryShippedPresetIsValid) {
  for (const auto& entry : fs::directory_iterator(test::sourceDir() / "presets")) {
    // base.yaml is a partial house style other presets extend, library.yaml the catalogue's library
    // file: neither is a preset of its own.
    const auto file = entry.path().filename();
    if (entry.path().extension() != ".yaml" || file == "base.yaml" || file == "library.yaml") continue;
    TempDir dir;
    // A coarse, short bake: validation and the whole path, not the look.
    const auto result = runRockbake({"bake", entry.path().string(), "-o", dir.path().string(), "--resolution", "40",
                                     "--set", "time=0.1", "--no-mesh"});
    EXPECT_EQ(result.exit_status, 0) << entry.path() << "\n" << result.output;
  }
}

}  // namespace
}  // namespace rockbake
