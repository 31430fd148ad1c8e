// The schema's table (docs/preset-reference.md): the reference page agrees with
// it, the enum names, the edit lists and the `extends` rules come from it, and
// every kind it lists merges as an alternative.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "preset/schema.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using test::TempDir;
using test::writeText;

const char* const kBegin = "<!-- BEGIN keys: generated from baker/preset/schema.cpp";
const char* const kEnd = "<!-- END keys -->";

std::string readFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The page's generated block, after its BEGIN line and before its END line.
std::string generatedBlock(const std::string& page, std::size_t& begin, std::size_t& end) {
  begin = page.find(kBegin);
  end = page.find(kEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) return {};
  begin = page.find('\n', begin) + 1;
  return page.substr(begin, end - begin);
}

// With ROCKBAKE_WRITE_PRESET_REFERENCE set (`cmake --build build --target preset-reference`), the test
// writes the tables into the page instead.
TEST(PresetReference, TheKeyTablesAreTheSchemasTable) {
  const fs::path file = test::sourceDir() / "docs" / "preset-reference.md";
  std::string page = readFile(file);
  std::size_t begin = 0, end = 0;
  const std::string block = generatedBlock(page, begin, end);
  ASSERT_NE(begin, std::string::npos) << file << " has no generated block";
  const std::string tables = "\n" + schema::presetReferenceTables() + "\n";
  if (std::getenv("ROCKBAKE_WRITE_PRESET_REFERENCE")) {
    page.replace(begin, end - begin, tables);
    std::ofstream(file, std::ios::binary) << page;
    GTEST_SKIP() << "wrote " << file;
  }
  EXPECT_EQ(block, tables) << file
                           << " disagrees with baker/preset/schema.cpp: "
                              "regenerate it with `cmake --build build --target preset-reference`";
}

// The page's example reads, beside the shipped base and the goblin image, as the shipped goblin.
TEST(PresetReference, TheExampleIsTheShippedGoblin) {
  const std::string page = readFile(test::sourceDir() / "docs" / "preset-reference.md");
  const std::size_t start = page.find("```yaml\n");
  ASSERT_NE(start, std::string::npos);
  const std::size_t body = start + 8;
  const std::string example = page.substr(body, page.find("```", body) - body);
  TempDir dir;
  const fs::path presets = test::sourceDir() / "presets";
  writeText(dir.path() / "goblin.yaml", example);
  writeText(dir.path() / "base.yaml", readFile(presets / "base.yaml"));
  writeText(dir.path() / "shapes" / "goblin.png", readFile(presets / "shapes" / "goblin.png"));
  nlohmann::json shown = presetToJson(loadPreset(dir.path() / "goblin.yaml"));
  nlohmann::json shipped = presetToJson(loadPreset(presets / "goblin.yaml"));
  EXPECT_EQ(shown["shape"]["image"]["path"], (dir.path() / "shapes" / "goblin.png").string());
  shown["shape"]["image"].erase("path");
  shipped["shape"]["image"].erase("path");
  EXPECT_EQ(shown, shipped);
}

// Each enum's names, read and written by the same table.
template <class E>
void expectNamesRoundTrip(const std::string& key_path, const std::string& head) {
  for (const auto& [value, name] : schema::enumNames<E>()) {
    EXPECT_EQ(schema::valueNamed<E>(name), value) << name;
    EXPECT_STREQ(schema::nameOf(value), name);
    PresetOverrides o;
    o.sets = {key_path + "=" + name};
    const nlohmann::json j = presetToJson(parsePreset(head, "p.yaml", o));
    nlohmann::json at = j;
    std::stringstream parts(key_path);
    for (std::string part; std::getline(parts, part, '.');) at = at[part];
    EXPECT_EQ(at, name) << key_path;
  }
  EXPECT_FALSE(schema::valueNamed<E>("no-such-name"));
}

TEST(Schema, EnumNamesAreReadAndWrittenByOneTable) {
  const std::string head = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n";
  expectNamesRoundTrip<Palette>("bake.palette", head);
  expectNamesRoundTrip<RockfallMode>("rockfall.mode", head);
  expectNamesRoundTrip<HullNaming>("collision.naming", head);
  EXPECT_EQ(schema::namesOf<ImageMode>(), (std::vector<std::string>{"extrude", "revolve"}));
  EXPECT_EQ(schema::namesOf<BubbleSpec::Kind>(),
            (std::vector<std::string>{"sphere", "ellipsoid", "box", "collection"}));
  EXPECT_EQ(schema::namesOf<ResponseParams::Kind>(), (std::vector<std::string>{"power", "threshold", "curve"}));
}

TEST(Schema, TheEditableKeysAreMarkedInTheTable) {
  EXPECT_EQ(schema::keyframedKeys(),
            (std::vector<std::string>{"durability.points", "durability.noise", "bubbles", "response"}));
  EXPECT_EQ(schema::resumableKeys(), (std::vector<std::string>{"rockfall", "colluvium", "time", "cycles", "until"}));
  EXPECT_EQ(schema::keyframePartOf("durability.noise.1.period"), schema::KeyframePart::Graph);
  EXPECT_EQ(schema::keyframePartOf("bubbles.0.up_to"), schema::KeyframePart::Bubbles);
  EXPECT_EQ(schema::keyframePartOf("response"), schema::KeyframePart::Response);
  // A keyframe's own keys are edited with the keyframes list, not as keyframed keys.
  EXPECT_FALSE(schema::keyframePartOf("durability.keyframes.0.points"));
  EXPECT_FALSE(schema::keyframePartOf("durability"));
  EXPECT_FALSE(schema::keyframePartOf("colluvium.yield"));
}

TEST(Schema, SettingOneOfTimeAndCyclesRemovesTheOther) {
  EXPECT_EQ(schema::siblingsReplacedBy("time"), std::vector<std::string>{"cycles"});
  EXPECT_EQ(schema::siblingsReplacedBy("cycles"), std::vector<std::string>{"time"});
  EXPECT_TRUE(schema::siblingsReplacedBy("shape.sphere").empty());
  EXPECT_TRUE(schema::siblingsReplacedBy("colluvium.yield").empty());
}

// Every kind of a one-of map replaces a base's other kind under `extends`: the merge rules are the
// table's kinds, so a kind added to the table cannot be forgotten there.
TEST(Schema, EveryKindReplacesTheBasesKindUnderExtends) {
  TempDir dir;
  writeText(dir.path() / "s.png", readFile(test::sourceDir() / "presets" / "shapes" / "goblin.png"));
  writeText(dir.path() / "b.obj", readFile(test::sourceDir() / "presets" / "shapes" / "boulder.obj"));
  const std::vector<std::pair<std::string, std::string>> shapes = {{"box", "{size: [1, 1, 1]}"},
                                                                   {"cylinder", "{radius: 1, height: 2}"},
                                                                   {"sphere", "{radius: 1}"},
                                                                   {"inside_corner", "{size: [2, 2, 2], wall: 0.5}"},
                                                                   {"image", "{path: s.png, height: 2}"},
                                                                   {"mesh", "{path: b.obj}"}};
  const std::vector<std::pair<std::string, std::string>> responses = {
      {"power", "2"}, {"threshold", "0.5"}, {"curve", "[[0, 0], [1, 1]]"}};
  for (const auto& [base_kind, base_value] : shapes)
    for (const auto& [kind, value] : shapes) {
      writeText(dir.path() / "base.yaml", "rockbake: 1\ntime: 1\nshape: {" + base_kind + ": " + base_value + "}\n");
      writeText(dir.path() / "p.yaml", "extends: base.yaml\nname: p\nshape: {" + kind + ": " + value + "}\n");
      EXPECT_NO_THROW(loadPreset(dir.path() / "p.yaml")) << base_kind << " under " << kind;
    }
  for (const auto& [base_kind, base_value] : responses)
    for (const auto& [kind, value] : responses) {
      writeText(dir.path() / "base.yaml", "rockbake: 1\ntime: 1\nshape: {sphere: {radius: 1}}\nresponse: {" +
                                              base_kind + ": " + base_value + "}\n");
      writeText(dir.path() / "p.yaml", "extends: base.yaml\nname: p\nresponse: {" + kind + ": " + value + "}\n");
      const Preset p = loadPreset(dir.path() / "p.yaml");
      EXPECT_TRUE(presetToJson(p)["response"].contains(kind)) << base_kind << " under " << kind;
    }
  // What the rules say, for the reference: each set of alternatives, and noise going with its points.
  const auto& rules = schema::mergeRules();
  const auto has = [&](const std::string& path, const std::vector<std::string>& given,
                       const std::vector<std::string>& drops) {
    return std::any_of(rules.begin(), rules.end(), [&](const schema::MergeRule& r) {
      return r.path == path && r.when_given == given && r.drops == drops;
    });
  };
  EXPECT_TRUE(has("", {"time", "cycles"}, {"time", "cycles"}));
  EXPECT_TRUE(has("durability", {"points"}, {"noise"}));
}

// The durability graph's noise and the mesh's detail are one NoiseParams, read by one row set: a
// period is a length (at most 1e+06 world units) in both.
TEST(Schema, NoiseIsReadAlikeForTheGraphAndTheMeshDetail) {
  const std::string head = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n";
  const auto error = [&](const std::string& yaml) {
    try {
      parsePreset(head + yaml, "p.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("mesh: {detail: {period: 2e6}}\n").find("mesh.detail.period: must be at most 1e+06 world units"),
            std::string::npos);
  EXPECT_NE(error("durability: {points: [[0, 1], [1, 1]], noise: [{period: 2e6}]}\n")
                .find("durability.noise.0.period: must be at most 1e+06 world units"),
            std::string::npos);
  EXPECT_NE(error("mesh: {detail: {octaves: 9}}\n").find("mesh.detail.octaves: must be a whole number from 1 to 8"),
            std::string::npos);
}

}  // namespace
}  // namespace rockbake
