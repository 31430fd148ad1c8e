// The studio's foundations (docs/model.md §4, docs/studio.md): keyframes that carry bubbles and
// response, simulation snapshots that resume exactly, keyframes replaced while
// running, and StudioSession's edits, seeks, branches and save contract.
#include <gtest/gtest.h>

#include <regex>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "export/vdb_file.h"
#include "inputs/resolve_shape.h"
#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "sim/grid_layout.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "studio/studio_session.h"
#include "test_support.h"

namespace rockbake {
namespace {

using test::TempDir;

// The small box preset with more cycles, colluvium and rockfall on (the
// state a snapshot must carry: accumulators, fallen rock).
Preset longSmallPreset(const TempDir& dir, const std::string& extra = "") {
  return parsePreset(std::string(test::kSmallPreset) + extra, dir.path() / "small.yaml",
                     {{"time=1.5"}, std::nullopt, std::nullopt});
}

void expectSameRock(const VoxelRock& a, const VoxelRock& b) {
  ASSERT_EQ(a.layout.cellCount(), b.layout.cellCount());
  EXPECT_TRUE(a.material == b.material);
  EXPECT_TRUE(a.integrity.toDense() == b.integrity.toDense());
  EXPECT_TRUE(a.durability.toDense() == b.durability.toDense());
}

TEST(Snapshot, ResumingASnapshotEqualsRunningStraightOn) {
  TempDir dir;
  const Preset preset = longSmallPreset(dir);
  const VoxelRock start = buildInitialRock(resolveShape(preset), preset);
  WeatheringSimulation straight(start, preset);
  WeatheringSimulation first(start, preset);
  for (int c = 0; c < 7; ++c) first.step();
  SimulationSnapshot snapshot = first.snapshot();
  EXPECT_EQ(snapshot.cycle, 7);
  WeatheringSimulation resumed(std::move(snapshot), preset);
  EXPECT_EQ(resumed.cycle(), 7);
  while (!straight.finished()) straight.step();
  int cycles = 7;
  while (!resumed.finished()) resumed.step(), ++cycles;
  EXPECT_EQ(cycles, straight.cycle());
  expectSameRock(straight.rock(), resumed.rock());
  EXPECT_EQ(straight.pendingColluvium(), resumed.pendingColluvium());
  EXPECT_GT(straight.counts().colluvium, 0u) << "the test needs colluvium to mean anything";
  EXPECT_EQ(straight.counts().rock, resumed.counts().rock);
}

TEST(Snapshot, AnotherSimulationsSnapshotDoesNotFit) {
  TempDir dir;
  const Preset preset = longSmallPreset(dir);
  WeatheringSimulation sim(buildInitialRock(resolveShape(preset), preset), preset);
  SimulationSnapshot snapshot = sim.snapshot();
  snapshot.colluvium_columns.pop_back();
  EXPECT_THROW(WeatheringSimulation(std::move(snapshot), preset), std::invalid_argument);
}

TEST(Keyframes, BubblesAndResponseKeyframesReadAndChangeTheRockFromTheirTime) {
  TempDir dir;
  const std::string keyframe = R"(durability:
  keyframes:
    - {at: 0.75, bubbles: [{up_to: 1.0, bubble: {sphere: {radius: 0.5}}, spheroidal: 0.2, cavernous: 1.0}],
       response: {power: 3.0}}
)";
  const Preset edited = longSmallPreset(dir, keyframe);
  ASSERT_EQ(edited.durability.keyframes.size(), 1u);
  const DurabilityKeyframe& k = edited.durability.keyframes[0];
  EXPECT_FALSE(k.graph);
  ASSERT_TRUE(k.bubbles && k.response);
  EXPECT_EQ((*k.bubbles)[0].bubble.extents[0], 0.5);
  EXPECT_EQ(k.response->value, 3.0);
  const nlohmann::json j = presetToJson(edited)["durability"]["keyframes"][0];
  EXPECT_FALSE(j.contains("points"));
  EXPECT_EQ(j["response"]["power"], 3.0);
  EXPECT_EQ(j["bubbles"][0]["cavernous"], 1.0);
  // The margin makes room for the keyframe's larger bubble.
  const Preset plain = longSmallPreset(dir);
  EXPECT_GT(computeGridLayout(edited).margin, computeGridLayout(plain).margin);

  // Same margin for both so the rocks compare voxel for voxel.
  Preset same_grid = plain;
  DurabilityKeyframe far = k;
  far.at = 100.0;  // never reached: only widens the margin
  same_grid.durability.keyframes = {far};
  const VoxelRock start = buildInitialRock(resolveShape(edited), edited);
  const WeatheringResult a = weatherRock(start, same_grid);
  const WeatheringResult b = weatherRock(start, edited);
  const int at_cycle = int(std::ceil(0.75 / start.layout.h - 1e-9));
  for (int c = 0; c < at_cycle; ++c) EXPECT_EQ(a.cycles[std::size_t(c)].rock, b.cycles[std::size_t(c)].rock) << c;
  EXPECT_NE(a.rock.material, b.rock.material) << "the keyframe changed nothing";
}

TEST(Keyframes, AKeyframeNeedsSomethingToChange) {
  TempDir dir;
  try {
    longSmallPreset(dir, "durability:\n  keyframes:\n    - {at: 0.5}\n");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("durability.keyframes.0: a keyframe needs 'points'"), std::string::npos)
        << e.what();
  }
}

TEST(Keyframes, SetWhileRunningEqualsTheSameKeyframesFromTheStart) {
  TempDir dir;
  const Preset plain = longSmallPreset(dir);
  const VoxelRock start = buildInitialRock(resolveShape(plain), plain);
  const double h = start.layout.h;
  DurabilityKeyframe k;
  k.at = 5 * h;
  k.graph = DurabilityGraph{{{0.0, 0.3}, {1.0, 3.0}}, {}};
  k.response = ResponseParams{ResponseParams::Kind::Power, 2.0, {}};
  Preset with = plain;
  with.durability.keyframes = {k};

  WeatheringSimulation running(start, plain);
  for (int c = 0; c < 5; ++c) running.step();
  running.setKeyframes({k});
  while (!running.finished()) running.step();
  const WeatheringResult baked = weatherRock(start, with);
  expectSameRock(baked.rock, running.rock());
  const WeatheringResult without = weatherRock(start, plain);
  EXPECT_NE(without.rock.material, baked.rock.material) << "the keyframe changed nothing";

  // A keyframe already reached cannot be taken back.
  WeatheringSimulation past(start, with);
  for (int c = 0; c < 7; ++c) past.step();
  EXPECT_THROW(past.setKeyframes({}), std::invalid_argument);
}

// ---- StudioSession ----

std::filesystem::path goblinFolder(const TempDir& dir) {
  namespace fs = std::filesystem;
  const fs::path presets = test::sourceDir() / "presets";
  fs::copy_file(presets / "goblin.yaml", dir.path() / "goblin.yaml");
  fs::copy_file(presets / "base.yaml", dir.path() / "base.yaml");
  fs::create_directories(dir.path() / "shapes");
  fs::copy_file(presets / "shapes" / "goblin.png", dir.path() / "shapes" / "goblin.png");
  return dir.path() / "goblin.yaml";
}

// What `rockbake bake FILE --no-mesh --resolution R` writes as rock.vdb.
std::string bakedVdb(const std::filesystem::path& file, int resolution, const TempDir& dir) {
  const Preset preset = loadPreset(file, {{}, std::nullopt, resolution});
  const WeatheringResult result = weatherRock(buildInitialRock(resolveShape(preset), preset), preset);
  const auto out = dir.path() / "baked.vdb";
  writeRockVdb(result.rock, out);
  return test::readBytes(out);
}

TEST(StudioSession, EditsSeeksAndABranchSaveAPresetThatBakesToTheSameRock) {
  TempDir dir;
  const auto file = goblinFolder(dir);
  StudioSession studio(file, 24);
  EXPECT_EQ(studio.cycle(), 0);
  const double h = studio.h();
  studio.edit({{"durability", {{"points", {{0.0, 2.0}, {0.5, 0.5}, {1.0, 1.5}}}}}});
  EXPECT_TRUE(studio.preset().durability.keyframes.empty());
  studio.runUntil(3 * h);
  studio.edit({{"durability", {{"points", {{0.0, 2.0}, {0.5, 0.2}, {1.0, 1.5}}}}}});
  studio.runUntil(6 * h);
  studio.edit({{"response", {{"power", 1.0}}}});
  ASSERT_EQ(studio.preset().durability.keyframes.size(), 2u);
  studio.runUntil(9 * h);
  const std::string at9 = studio.rockVdb();

  studio.seek(2 * h);
  EXPECT_EQ(studio.cycle(), 2);
  studio.seek(9 * h);
  EXPECT_EQ(studio.rockVdb(), at9) << "seeking back and forth changed the rock";

  // Branch at cycle 4: the keyframe at 6h goes, the one at 3h stays.
  studio.seek(4 * h);
  nlohmann::json bands = studio.state()["active"]["bubbles"];
  bands[0]["cavernous"] = 0.8;
  studio.edit({{"bubbles", bands}});
  ASSERT_EQ(studio.preset().durability.keyframes.size(), 2u);
  EXPECT_DOUBLE_EQ(studio.preset().durability.keyframes[1].at, 4 * h);
  EXPECT_FALSE(studio.preset().durability.keyframes[1].response);
  studio.runUntil(8 * h);
  EXPECT_NE(studio.rockVdb(), at9);

  const SaveResult saved = studio.save("goblin-branch", false);
  EXPECT_EQ(saved.path, dir.path() / "goblin-branch.yaml");
  EXPECT_DOUBLE_EQ(saved.time, 8 * h);
  EXPECT_EQ(bakedVdb(saved.path, 24, dir), studio.rockVdb());
  EXPECT_EQ(loadPreset(saved.path).name, "goblin-branch");
}

// Run to the preset's end, a save keeps the preset's own `time` (not the end snapped to preview
// cycles, which would make the final bake at the preset's resolution run a cycle more); the
// saved preset still bakes the studio's rock at the studio's resolution.
TEST(StudioSession, ASaveAtTheRunsEndKeepsThePresetsTime) {
  TempDir dir;
  const auto file = goblinFolder(dir);
  std::string text = test::readBytes(file);
  text = std::regex_replace(text, std::regex("\ntime: [^\n]*"), "\ntime: 0.8");
  test::writeText(file, text);
  const Preset own = loadPreset(file);
  ASSERT_EQ(own.stop.time, 0.8);
  StudioSession studio(file, 24);
  const double end = studio.state()["end_time"].get<double>();
  ASSERT_NE(end, *own.stop.time) << "pick a preview resolution whose cycles do not end on the preset's time";
  studio.runUntil(end);
  ASSERT_TRUE(studio.atEnd());
  const SaveResult saved = studio.save("goblin-end", false);
  const Preset reread = loadPreset(saved.path);
  ASSERT_TRUE(reread.stop.time.has_value());
  EXPECT_EQ(*reread.stop.time, *own.stop.time);
  EXPECT_FALSE(reread.stop.cycles.has_value());
  EXPECT_EQ(bakedVdb(saved.path, 24, dir), studio.rockVdb());
}

TEST(StudioSession, RefusesEditsAndSavesItCannotHonour) {
  TempDir dir;
  const auto file = goblinFolder(dir);
  StudioSession studio(file, 24);
  const auto status = [&](auto&& call) {
    try {
      call();
    } catch (const StudioError& e) {
      return e.status();
    }
    return 200;
  };
  EXPECT_EQ(status([&] { studio.edit({{"durability", {{"points", {{0.0, -1.0}, {1.0, 1.0}}}}}}); }), 400);
  EXPECT_EQ(status([&] { studio.edit({{"grid", {{"resolution", 100}}}}); }), 400);
  EXPECT_EQ(status([&] { studio.edit(nlohmann::json::array()); }), 400);
  EXPECT_EQ(status([&] { studio.save("goblin-x", false); }), 409) << "time 0 bakes one cycle: not what is shown";
  studio.step();
  EXPECT_EQ(status([&] { studio.save("../goblin-x", false); }), 400);
  EXPECT_EQ(status([&] { studio.save("-rf", false); }), 400) << "lint *.yaml would read it as an option";
  EXPECT_EQ(status([&] { studio.save("goblin", true); }), 409);
  EXPECT_EQ(status([&] { studio.save("base", true); }), 409);
  EXPECT_EQ(status([&] { studio.seek(-1); }), 400);
  EXPECT_EQ(status([&] {
              studio.edit({{"bubbles", {{{"up_to", 1.0}, {"bubble", {{"sphere", {{"radius", 1.9}}}}}}}}});
            }),
            400);
  EXPECT_EQ(studio.cycle(), 1);
  EXPECT_TRUE(studio.preset().durability.keyframes.empty());
}

}  // namespace
}  // namespace rockbake
