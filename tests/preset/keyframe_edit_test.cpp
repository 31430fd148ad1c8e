// One keyframe edit for the studio and `resume` (preset/keyframe_edit.h, docs/preset-reference.md):
// times match within a billionth of a cycle, an edit merges into a keyframe at its time, and the
// keyframes after it are dropped.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "preset/keyframe_edit.h"
#include "preset/load_preset.h"
#include "preset/preset_json.h"

namespace rockbake {
namespace {

constexpr double kH = 0.05;  // a cycle's time in these presets' terms

Preset withKeyframes() {
  return parsePreset(R"(rockbake: 1
name: p
shape: {box: {size: [1, 1, 1]}}
time: 2
durability:
  keyframes:
    - {at: 0, response: {power: 3}, bubbles: [{up_to: 1, bubble: {sphere: {radius: 0.5}}}]}
    - {at: 0.3, response: {power: 2}}
    - {at: 0.6, points: [[0, 2], [1, 2]]}
    - {at: 0.9, response: {threshold: 0.5}}
)",
                     "p.yaml");
}

KeyframeEdit responseEdit(double power) {
  KeyframeEdit edit;
  edit.response = ResponseParams{ResponseParams::Kind::Power, power, {}};
  return edit;
}

TEST(KeyframeEdit, TimesMatchWithinABillionthOfACycle) {
  EXPECT_TRUE(sameKeyframeTime(0.3, 6 * kH, kH));  // 0.30000000000000004
  EXPECT_NE(0.3, 6 * kH);
  EXPECT_TRUE(sameKeyframeTime(1.0, 1.0 + 0.9e-9 * kH, kH));
  EXPECT_FALSE(sameKeyframeTime(1.0, 1.0 + 1.1e-9 * kH, kH));
  EXPECT_FALSE(sameKeyframeTime(0.3, 0.35, kH));
}

TEST(KeyframeEdit, AnEditAtAKeyframesTimeMergesIntoItAndDropsTheLaterOnes) {
  Preset p = withKeyframes();
  const std::vector<double> dropped = applyKeyframeEdit(p, responseEdit(1.5), 6 * kH, kH);
  EXPECT_EQ(dropped, (std::vector<double>{0.6, 0.9}));
  const auto& k = p.durability.keyframes;
  ASSERT_EQ(k.size(), 2u);
  EXPECT_EQ(k[1].at, 6 * kH) << "the keyframe takes the edit's time exactly";
  EXPECT_EQ(k[1].response->value, 1.5);
  EXPECT_FALSE(k[1].graph);
  EXPECT_EQ(k[0].response->value, 3.0) << "earlier keyframes stay";
}

TEST(KeyframeEdit, AnEditBetweenKeyframesAddsOneAfterTheEarlierOnes) {
  Preset p = withKeyframes();
  KeyframeEdit edit;
  edit.graph = DurabilityGraph{{{0.0, 0.5}, {1.0, 4.0}}, {}};
  EXPECT_EQ(applyKeyframeEdit(p, edit, 9 * kH, kH), (std::vector<double>{0.6, 0.9}));
  const auto& k = p.durability.keyframes;
  ASSERT_EQ(k.size(), 3u);
  EXPECT_EQ(k[2].at, 9 * kH);
  EXPECT_EQ(k[2].graph->points[1][1], 4.0);
  EXPECT_FALSE(k[2].response);
  // Reading the result back gives the same preset: it is a valid one.
  EXPECT_EQ(presetToJson(parsePreset(presetToJson(p).dump(), "p.yaml")), presetToJson(p));
}

TEST(KeyframeEdit, AnEditAtTimeZeroChangesThePresetItself) {
  Preset p = withKeyframes();
  EXPECT_EQ(applyKeyframeEdit(p, responseEdit(1.25), 0.0, kH), (std::vector<double>{0.3, 0.6, 0.9}));
  EXPECT_EQ(p.response.value, 1.25);
  // The keyframe at 0 would replace the edit at once: it loses the response and keeps its bubbles.
  ASSERT_EQ(p.durability.keyframes.size(), 1u);
  EXPECT_FALSE(p.durability.keyframes[0].response);
  EXPECT_TRUE(p.durability.keyframes[0].bubbles);
  // A keyframe left with nothing is dropped.
  KeyframeEdit bubbles;
  bubbles.bubbles = p.bubbles;
  applyKeyframeEdit(p, bubbles, 0.0, kH);
  EXPECT_TRUE(p.durability.keyframes.empty());
}

TEST(KeyframeEdit, KeyPathsNameTheParts) {
  PresetOverrides o;
  o.sets = {"response={threshold: 0.25}", "colluvium.yield=0.1"};
  const Preset edited = parsePreset("rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 2\n", "p.yaml", o);
  const KeyframeEdit edit = keyframeEditOf(edited, {"response", "colluvium.yield", "durability.noise"});
  ASSERT_TRUE(edit.response);
  EXPECT_EQ(edit.response->kind, ResponseParams::Kind::Threshold);
  ASSERT_TRUE(edit.graph) << "noise is part of the graph";
  EXPECT_EQ(edit.graph->points, edited.durability.graph.points);
  EXPECT_FALSE(edit.bubbles);
  EXPECT_TRUE(keyframeEditOf(edited, {"colluvium", "durability.keyframes.0.at"}).empty());
  EXPECT_TRUE(keyframeEditOf(edited, {"bubbles.0.cavernous"}).bubbles);
}

}  // namespace
}  // namespace rockbake
