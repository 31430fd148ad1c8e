// The preset's `look:` block (docs/textures.md, "The look"): read, written back, turned off with
// `look: none` (over a base that has one too), and refused with the place and the problem.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "preset/read_preset.h"
#include "test_support.h"

namespace rockbake {
namespace {

const std::string kBase = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ncycles: 5\n";

std::string errorOf(const std::string& yaml) {
  try {
    parsePreset(yaml, "dir/p.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Look, ReadsEveryEffectItsColoursAndItsRelief) {
  const Preset p = parsePreset(kBase +
                                   "look:\n"
                                   "  stain: 2\n"
                                   "  varnish: 0.5\n"
                                   "  dust: 0\n"
                                   "  lichen: 1.5\n"
                                   "  colors: {varnish: '#102030', dust: [0.5, 0.25, 1]}\n"
                                   "  laminations: {amplitude: 0.01, spacing: 0.1}\n"
                                   "  pitting: {amplitude: 0.02}\n",
                               "p.yaml");
  ASSERT_TRUE(p.look);
  const LookParams& look = *p.look;
  EXPECT_EQ(look.stain, 2.0);
  EXPECT_EQ(look.varnish, 0.5);
  EXPECT_EQ(look.dust, 0.0);
  EXPECT_EQ(look.moisture, 1.0);  // the default
  EXPECT_EQ(look.lichen, 1.5);
  EXPECT_DOUBLE_EQ(look.varnish_color[0], 0x10 / 255.0);
  EXPECT_DOUBLE_EQ(look.varnish_color[2], 0x30 / 255.0);
  EXPECT_EQ(look.dust_color, (SrgbColor{0.5, 0.25, 1.0}));
  EXPECT_EQ(look.stain_color, LookParams{}.stain_color);
  EXPECT_EQ(look.laminations.amplitude, 0.01);
  EXPECT_EQ(look.laminations.spacing, 0.1);
  EXPECT_EQ(look.pitting.amplitude, 0.02);
  EXPECT_EQ(look.pitting.spacing, LookParams{}.pitting.spacing);
  // Written back, it reads as itself.
  const nlohmann::json json = presetToJson(p);
  ASSERT_TRUE(json.contains("look"));
  EXPECT_EQ(json["look"]["stain"], 2.0);
  EXPECT_EQ(presetToJson(parsePreset(json.dump(), "p.yaml")), json);
}

TEST(Look, NoneOrLeftOutIsNoLookAndLeavesTheJsonAsItWas) {
  const Preset without = parsePreset(kBase, "p.yaml");
  const Preset none = parsePreset(kBase + "look: none\n", "p.yaml");
  EXPECT_FALSE(without.look);
  EXPECT_FALSE(none.look);
  // The same resolved preset, so the same input hash as a preset written before looks existed.
  EXPECT_EQ(presetToJson(none), presetToJson(without));
  EXPECT_FALSE(presetToJson(none).contains("look"));
  EXPECT_TRUE(parsePreset(kBase + "look: {}\n", "p.yaml").look);
}

TEST(Look, NoneTurnsOffTheLookABaseGives) {
  test::TempDir dir;
  test::writeText(dir.path() / "base.yaml", "rockbake: 1\nlook: {stain: 2, dust: 3}\n");
  test::writeText(dir.path() / "plain.yaml", "extends: base.yaml\n" + kBase);
  test::writeText(dir.path() / "none.yaml", "extends: base.yaml\n" + kBase + "look: none\n");
  test::writeText(dir.path() / "less.yaml", "extends: base.yaml\n" + kBase + "look: {dust: 0}\n");
  const Preset plain = loadPreset(dir.path() / "plain.yaml");
  ASSERT_TRUE(plain.look);
  EXPECT_EQ(plain.look->stain, 2.0);
  EXPECT_FALSE(loadPreset(dir.path() / "none.yaml").look);
  const Preset less = loadPreset(dir.path() / "less.yaml");  // merged key by key
  ASSERT_TRUE(less.look);
  EXPECT_EQ(less.look->stain, 2.0);
  EXPECT_EQ(less.look->dust, 0.0);
}

TEST(Look, BadInputNamesFileLineColumnAndKeyPath) {
  const std::string unknown = errorOf(kBase + "look: {stian: 1}\n");
  EXPECT_NE(unknown.find("dir/p.yaml:5:8: look.stian: unknown key 'stian'; did you mean 'stain'?"), std::string::npos)
      << unknown;
  const std::string negative = errorOf(kBase + "look:\n  dust: -0.5\n");
  EXPECT_NE(negative.find("dir/p.yaml:6:9: look.dust: must be in [0, 4]"), std::string::npos) << negative;
  const std::string strong = errorOf(kBase + "look: {varnish: 5}\n");
  EXPECT_NE(strong.find("look.varnish: must be in [0, 4]"), std::string::npos) << strong;
  const std::string colour = errorOf(kBase + "look: {colors: {dust: sandy}}\n");
  EXPECT_NE(colour.find("dir/p.yaml:5:23: look.colors.dust: 'sandy' is not a colour"), std::string::npos) << colour;
  const std::string relief = errorOf(kBase + "look: {pitting: {amplitude: -1}}\n");
  EXPECT_NE(relief.find("look.pitting.amplitude:"), std::string::npos) << relief;
  const std::string spacing = errorOf(kBase + "look: {laminations: {spacing: 0}}\n");
  EXPECT_NE(spacing.find("look.laminations.spacing:"), std::string::npos) << spacing;
  const std::string word = errorOf(kBase + "look: off\n");
  EXPECT_NE(word.find("dir/p.yaml:5:7: look:"), std::string::npos) << word;
}

TEST(Look, ABadLookExitsWithTwoAndWritesNothing) {
  test::TempDir dir;
  const std::filesystem::path preset = dir.path() / "small.yaml";
  test::writeText(preset, std::string(test::kSmallPreset) + "look: {stain: 1, dust: -1}\n");
  const std::filesystem::path out = dir.path() / "out";
  const test::CommandResult bad = test::runRockbake({"bake", preset.string(), "-o", out.string(), "--no-render"});
  EXPECT_EQ(bad.exit_status, 2) << bad.output;
  EXPECT_NE(bad.output.find("small.yaml:13:"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("look.dust: must be in [0, 4]"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const test::CommandResult set = test::runRockbake({"bake", (test::sourceDir() / "presets" / "goblin.yaml").string(),
                                                     "-o", out.string(), "--set", "look.colors.varnish=brown"});
  EXPECT_EQ(set.exit_status, 2) << set.output;
  EXPECT_NE(set.output.find("look.colors.varnish"), std::string::npos) << set.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace rockbake
