// The studio and `rockbake resume` edit a run by one rule (preset/keyframe_edit.h): the same
// edits at the same times, whether made in the studio (with seeks back) or by resuming
// checkpoints with --set, give the same preset.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "pipeline/manifest.h"
#include "pipeline/resume_plan.h"
#include "preset/preset_json.h"
#include "studio/studio_session.h"
#include "test_support.h"

namespace rockbake {
namespace {

using nlohmann::json;
using test::TempDir;

constexpr int kResolution = 40;  // h = 2 / 40 = 0.05

// The small preset with keyframes of its own: one at 0.3, which is cycle 6 (6 × 0.05 is
// 0.30000000000000004 in binary), and a later one.
const std::string kPreset = std::string(test::kSmallPreset) + R"(durability:
  keyframes:
    - {at: 0.3, response: {power: 1.5}}
    - {at: 0.75, points: [[0, 2], [1, 0.5]]}
)";

// A checkpoint of the run that `overrides` bake, at `cycle`, as `resume` reads it.
Checkpoint checkpointAt(const std::filesystem::path& file, const PresetOverrides& overrides, int cycle, double h) {
  Checkpoint c;
  c.preset_file = file;
  c.preset_text = kPreset;
  c.overrides = overrides;
  c.preset_hash = presetFingerprint(parsePreset(kPreset, file, overrides), {});
  c.snapshot.cycle = cycle;
  c.snapshot.rock.layout.h = h;
  return c;
}

TEST(KeyframeAgreement, TheStudioAndResumeGiveTheSamePresetForTheSameEdits) {
  TempDir dir;
  const auto file = dir.path() / "small.yaml";
  test::writeText(file, kPreset);
  StudioSession studio(file, kResolution);
  const double h = studio.h();
  PresetOverrides run = {{}, std::nullopt, kResolution};
  const auto resume = [&](int cycle, const std::vector<std::string>& sets) {
    const ResumePlan plan = planResume(checkpointAt(file, run, cycle, h), sets);
    run = plan.overrides;
    return presetToJson(plan.preset);
  };

  // At the preset's keyframe at 0.3 = 6 h: the edit merges into it; the one at 0.75 is dropped.
  ASSERT_NE(6 * h, 0.3);
  studio.runUntil(6 * h);
  studio.edit({{"response", {{"power", 2.0}}}});
  EXPECT_EQ(resume(6, {"response={power: 2.0}"}), presetToJson(studio.preset()));
  ASSERT_EQ(studio.preset().durability.keyframes.size(), 1u);
  EXPECT_EQ(studio.preset().durability.keyframes[0].at, 6 * h);

  // Later: a new keyframe with the graph.
  const json points = {{0.0, 0.5}, {0.5, 2.0}, {1.0, 0.7}}, noise = {nullptr, {{"amplitude", 0.2}}};
  studio.runUntil(9 * h);
  studio.edit({{"durability", {{"points", points}, {"noise", noise}}}});
  EXPECT_EQ(resume(9, {"durability.points=" + points.dump(), "durability.noise=" + noise.dump()}),
            presetToJson(studio.preset()));
  ASSERT_EQ(studio.preset().durability.keyframes.size(), 2u);

  // Back to 7 h: a branch, the keyframe at 9 h goes.
  json bands = studio.state()["active"]["bubbles"];
  bands[0]["cavernous"] = 0.9;
  studio.seek(7 * h);
  studio.edit({{"bubbles", bands}});
  EXPECT_EQ(resume(7, {"bubbles=" + bands.dump()}), presetToJson(studio.preset()));
  ASSERT_EQ(studio.preset().durability.keyframes.size(), 2u);
  EXPECT_TRUE(studio.preset().durability.keyframes[1].bubbles);

  // Back to 6 h: into the keyframe there, and the one at 7 h goes.
  studio.seek(6 * h);
  studio.edit({{"response", {{"threshold", 0.4}}}});
  EXPECT_EQ(resume(6, {"response={threshold: 0.4}"}), presetToJson(studio.preset()));
  ASSERT_EQ(studio.preset().durability.keyframes.size(), 1u);
  EXPECT_EQ(studio.preset().durability.keyframes[0].response->kind, ResponseParams::Kind::Threshold);
}

TEST(KeyframeAgreement, ResumeRefusesAKeyframedEditAtTimeZero) {
  TempDir dir;
  const auto file = dir.path() / "small.yaml";
  test::writeText(file, kPreset);
  const Checkpoint start = checkpointAt(file, {{}, std::nullopt, kResolution}, 0, 0.05);
  try {
    planResume(start, {"response={power: 2}"});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the checkpoint is at time 0"), std::string::npos) << e.what();
  }
  // What applies from the checkpoint on is still fine there.
  EXPECT_EQ(planResume(start, {"colluvium.yield=0.1"}).preset.colluvium.yield, 0.1);
}

}  // namespace
}  // namespace rockbake
