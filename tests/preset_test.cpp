// Preset loading and validation (SPEC §5, §6).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "test_support.h"
#include "util/error.h"

namespace rockbake {
namespace {

const char* kFull = R"(rockbake: 1
name: goblin
seed: 7
grid:
  size: [4.0, 4.0, 6.0]
  resolution: 96
  ground: true
shape:
  cylinder: {radius: 1.0, height: 3.0}
  center: [2.0, 2.0, 0.0]
durability:
  points: [[0.0, 2.0], [0.4, 0.6], [0.7, 3.0], [1.0, 1.5]]
  noise:
    - {amplitude: 0.3, period: 0.8, octaves: 3}
    - null
    - {amplitude: 0.5, period: 0.5, octaves: 2}
  keyframes:
    - {at: 2.0, points: [[0.0, 2.0], [0.5, 0.3], [1.0, 1.5]]}
bubbles:
  - up_to: 0.5
    bubble: {sphere: {radius: 0.3}}
    spheroidal: 1.0
    cavernous: 0.0
  - up_to: 1.0
    bubble: {collection: [{bubble: {sphere: {radius: 0.2}}, weight: 1.0},
                          {bubble: {ellipsoid: {radii: [0.5, 0.5, 0.25]}}, weight: 0.5}]}
    spheroidal: 0.6
    cavernous: 0.4
response: {threshold: 0.55}
rockfall: {mode: crumble}
colluvium: {yield: 0.5, talus_angle: 35, removal: 0.1}
time: 3.0
until: {rock_volume_fraction: 0.5}
mesh: {smoothing: 1.0, subdivision: 2, lods: [0.5, 0.25]}
bake: {palette: debug}
export: [ply, glb]
render: {template: studio, width: 640, height: 480, turntable: {frames: 8}}
)";

std::string errorOf(const std::string& yaml, const PresetOverrides& overrides = {}) {
  try {
    parsePreset(yaml, "dir/p.yaml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Preset, ReadsEveryKeyOfTheSchema) {
  const Preset p = parsePreset(kFull, "dir/p.yaml");
  EXPECT_EQ(p.name, "goblin");
  EXPECT_EQ(p.seed, 7u);
  EXPECT_EQ(p.grid.size[2], 6.0);
  EXPECT_EQ(p.grid.resolution, 96);
  ASSERT_TRUE(std::holds_alternative<CylinderShape>(p.shape.kind));
  EXPECT_EQ(std::get<CylinderShape>(p.shape.kind).radius, 1.0);
  ASSERT_TRUE(p.shape.center.has_value());
  ASSERT_EQ(p.durability.graph.points.size(), 4u);
  ASSERT_EQ(p.durability.graph.noise.size(), 3u);
  EXPECT_FALSE(p.durability.graph.noise[1].has_value());
  EXPECT_EQ(p.durability.graph.noise[2]->octaves, 2);
  ASSERT_EQ(p.durability.keyframes.size(), 1u);
  EXPECT_EQ(p.durability.keyframes[0].at, 2.0);
  ASSERT_EQ(p.bubbles.size(), 2u);
  EXPECT_EQ(p.bubbles[1].bubble.kind, BubbleSpec::Kind::Collection);
  EXPECT_EQ(p.bubbles[1].bubble.members[1].bubble.extents[2], 0.25);
  EXPECT_EQ(p.bubbles[1].cavernous, 0.4);
  EXPECT_EQ(p.response.kind, ResponseParams::Kind::Threshold);
  EXPECT_EQ(p.response.value, 0.55);
  EXPECT_EQ(p.rockfall.mode, RockfallMode::Crumble);
  EXPECT_EQ(p.colluvium.removal, 0.1);
  EXPECT_EQ(*p.stop.time, 3.0);
  EXPECT_EQ(*p.stop.rock_volume_fraction, 0.5);
  EXPECT_EQ(p.mesh.lods.size(), 2u);
  EXPECT_EQ(p.bake.palette, Palette::Debug);
  EXPECT_EQ(p.exports, (std::vector<std::string>{"ply", "glb"}));
  EXPECT_EQ(p.render.turntable_frames, 8);
}

TEST(Preset, FillsDefaults) {
  const Preset p = parsePreset("rockbake: 1\nname: plain\nshape: {box: {size: [1, 1, 1]}}\ncycles: 5\n", "p.yaml");
  EXPECT_EQ(p.grid.resolution, 96);
  EXPECT_TRUE(p.grid.ground);
  EXPECT_EQ(p.durability.graph.points.size(), 2u);
  ASSERT_EQ(p.bubbles.size(), 1u);
  EXPECT_DOUBLE_EQ(p.bubbles[0].bubble.extents[0], 6.0 / 16.0);  // a sixteenth of the longest side
  EXPECT_EQ(p.response.kind, ResponseParams::Kind::Power);
  EXPECT_EQ(p.rockfall.mode, RockfallMode::Drop);
  EXPECT_EQ(*p.stop.cycles, 5);
  EXPECT_FALSE(p.stop.time.has_value());
}

TEST(Preset, ErrorsNameFileLineColumnAndKeyPath) {
  const std::string base = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ncycles: 5\n";
  // Malformed YAML: the position of the syntax error.
  EXPECT_NE(errorOf("rockbake: 1\nname: [p\n").find("dir/p.yaml:3:"), std::string::npos);
  // Wrong type.
  const std::string wrong_type = errorOf(base + "colluvium:\n  yield: lots\n");
  EXPECT_NE(wrong_type.find("dir/p.yaml:6:10: colluvium.yield: expected a number, found 'lots'"), std::string::npos)
      << wrong_type;
  // Unknown key with a suggestion, at the key.
  const std::string unknown = errorOf(base +
                                      "bubbles:\n  - up_to: 1\n    bubble: {sphere: {radius: 0.2}}\n"
                                      "    spherodial: 1\n");
  EXPECT_NE(unknown.find("dir/p.yaml:8:5: bubbles.0.spherodial: unknown key 'spherodial'; did you mean "
                         "'spheroidal'?"),
            std::string::npos)
      << unknown;
  // Out of range.
  const std::string range = errorOf(base + "colluvium: {talus_angle: 95}\n");
  EXPECT_NE(range.find("dir/p.yaml:5:26: colluvium.talus_angle: must be in (0, 90)"), std::string::npos) << range;
  // Nested list item paths.
  const std::string nested = errorOf(
      base + "bubbles:\n  - up_to: 1\n    bubble: {collection: [{bubble: {sphere: {radius: 0.2}}, weight: -1}]}\n");
  EXPECT_NE(nested.find("bubbles.0.bubble.collection.0.weight: must be greater than 0"), std::string::npos) << nested;
}

TEST(Preset, RejectsInconsistentPresets) {
  const std::string head = "rockbake: 1\nname: p\n";
  const std::string box = "shape: {box: {size: [1, 1, 1]}}\n";
  EXPECT_NE(errorOf(head + box).find("missing 'time'"), std::string::npos);
  EXPECT_NE(errorOf(head + box + "time: 1\ncycles: 3\n").find("not both"), std::string::npos);
  EXPECT_NE(errorOf(head + "shape: {box: {size: [1, 1, 1]}, sphere: {radius: 1}}\ntime: 1\n").find("exactly one"),
            std::string::npos);
  EXPECT_NE(errorOf(head + box +
                    "time: 1\nbubbles:\n  - {up_to: 0.6, bubble: {sphere: {radius: 0.2}}}\n"
                    "  - {up_to: 0.4, bubble: {sphere: {radius: 0.2}}}\n")
                .find("up_to must increase"),
            std::string::npos);
  EXPECT_NE(errorOf(head + box + "time: 1\nbubbles:\n  - {up_to: 0.6, bubble: {sphere: {radius: 0.2}}}\n")
                .find("the last band must reach 1"),
            std::string::npos);
  EXPECT_NE(errorOf(head + box + "time: 1\nbubbles:\n  - {up_to: 1, bubble: {sphere: {radius: 0.001}}}\n")
                .find("smaller than one voxel"),
            std::string::npos);
  EXPECT_NE(errorOf(head + box + "time: 1\ndurability: {points: [[0, 1], [0.5, 1]], noise: [null, null]}\n")
                .find("one entry per segment"),
            std::string::npos);
  EXPECT_NE(errorOf("rockbake: 1\nname: Bad Name\n" + box + "time: 1\n").find("may only use"), std::string::npos);
  EXPECT_NE(errorOf("rockbake: 2\nname: p\n" + box + "time: 1\n").find("rockbake: must be a whole number from 1 to 1"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "shape: {image: {path: missing.png, height: 1}}\ntime: 1\n").find("shape.image.path"),
            std::string::npos);
  // A grid far beyond this machine's memory is refused before allocation.
  EXPECT_NE(errorOf(head + box +
                    "time: 1\ngrid: {size: [1, 1, 1], resolution: 2048}\n"
                    "bubbles: [{up_to: 1, bubble: {sphere: {radius: 0.01}}}]\n")
                .find("grid.resolution"),
            std::string::npos);
}

TEST(Preset, PaletteColoursAreSrgbHexOrLists) {
  const Preset p = parsePreset(
      "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n"
      "bake:\n  palette: natural\n  layers:\n    - {durability: 0.5, color: '#E3C9A0'}\n"
      "    - {durability: 2.0, color: [0.4, 0.2, 0.1]}\n  colluvium_color: '#b49a78'\n",
      "p.yaml");
  ASSERT_EQ(p.bake.layers.size(), 2u);
  EXPECT_NEAR(p.bake.layers[0].color[0], 0xE3 / 255.0, 1e-12);
  EXPECT_EQ(p.bake.layers[1].color[2], 0.1);
  EXPECT_NEAR((*p.bake.colluvium_color)[1], 0x9a / 255.0, 1e-12);
  const std::string head = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n";
  EXPECT_NE(errorOf(head + "bake: {layers: [{durability: 1, color: 'red'}]}\n").find("'red' is not a colour"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "bake: {layers: [{durability: 1, color: [1, 2, 0]}]}\n")
                .find("bake.layers.0.color.1: must be in [0, 1]"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "bake: {layers: [{durability: 2, color: '#000000'}, {durability: 1, color: '#ffffff'}]}\n")
                .find("durability must increase"),
            std::string::npos);
}

TEST(Preset, ImagePathsResolveAgainstThePresetsFolder) {
  test::TempDir dir;
  test::writeText(dir.path() / "shapes" / "s.png", "not read here");
  const Preset p = parsePreset(
      "rockbake: 1\nname: p\nshape: {image: {path: shapes/s.png, mode: revolve, height: 2}}\n"
      "time: 1\n",
      dir.path() / "p.yaml");
  const auto& image = std::get<ImageShape>(p.shape.kind);
  EXPECT_EQ(image.path, dir.path() / "shapes" / "s.png");
  EXPECT_EQ(image.mode, ImageMode::Revolve);
}

TEST(Preset, SetOverridesApplyBeforeValidation) {
  PresetOverrides o;
  o.sets = {"colluvium.yield=0.3", "export=[ply, glb]", "bubbles.1.spheroidal=0.25", "grid.ground=false", "cycles=4"};
  o.seed = 99;
  o.resolution = 48;
  const Preset p = parsePreset(kFull, "p.yaml", o);
  EXPECT_EQ(p.colluvium.yield, 0.3);
  EXPECT_EQ(p.exports, (std::vector<std::string>{"ply", "glb"}));
  EXPECT_EQ(p.bubbles[1].spheroidal, 0.25);
  EXPECT_FALSE(p.grid.ground);
  EXPECT_EQ(*p.stop.cycles, 4);  // replaces the preset's time
  EXPECT_FALSE(p.stop.time.has_value());
  EXPECT_EQ(p.seed, 99u);
  EXPECT_EQ(p.grid.resolution, 48);

  const auto setError = [](const std::string& set) {
    PresetOverrides bad;
    bad.sets = {set};
    return errorOf(kFull, bad);
  };
  EXPECT_NE(setError("colluvium.yield").find("--set: 'colluvium.yield': expected key.path=VALUE"), std::string::npos);
  EXPECT_NE(setError("bubbles.7.spheroidal=1").find("past the end"), std::string::npos);
  EXPECT_NE(setError("colluvium.yield=[1, 2").find("not valid YAML"), std::string::npos);
  // A bad value that came from --set is located at the flag.
  EXPECT_NE(setError("colluvium.yield=3").find("--set colluvium.yield=3: colluvium.yield: must be in [0, 1]"),
            std::string::npos)
      << setError("colluvium.yield=3");
}

TEST(Preset, ResolvedJsonReadsLikeAPreset) {
  const Preset p = parsePreset(kFull, "p.yaml");
  const nlohmann::json j = presetToJson(p);
  EXPECT_EQ(j["name"], "goblin");
  EXPECT_EQ(j["grid"]["resolution"], 96);
  EXPECT_EQ(j["shape"]["cylinder"]["radius"], 1.0);
  EXPECT_EQ(j["bubbles"][1]["bubble"]["collection"][1]["bubble"]["ellipsoid"]["radii"][0], 0.5);
  EXPECT_EQ(j["response"]["threshold"], 0.55);
  EXPECT_TRUE(j["durability"]["noise"][1].is_null());
  EXPECT_EQ(j["durability"]["keyframes"][0]["at"], 2.0);
  EXPECT_EQ(j["rockfall"]["mode"], "crumble");
  EXPECT_EQ(j["time"], 3.0);
  EXPECT_FALSE(j.contains("cycles"));
  // The dump parses back into the same preset.
  const Preset again = parsePreset(j.dump(), "p.yaml");
  EXPECT_EQ(presetToJson(again), j);
}

}  // namespace
}  // namespace rockbake
