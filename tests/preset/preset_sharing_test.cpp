// Sharing presets (docs/libraries.md): extends, lint, preset show, override origins.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using test::runRockbake;
using test::TempDir;
using test::writeText;

std::string loadError(const fs::path& file, const PresetOverrides& overrides = {}) {
  try {
    loadPreset(file, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// "file:line:col: key.path" of each problem, in order.
std::vector<std::string> lintLocations(const fs::path& file) {
  std::vector<std::string> out;
  for (const auto& problem : lintPreset(file))
    out.push_back(problem.where().file + ":" + std::to_string(problem.where().line) + ":" +
                  std::to_string(problem.where().column) + ": " + problem.keyPath());
  return out;
}

// A partial house style: no name, no shape.
const char* kBase = R"(rockbake: 1
grid: {size: [2.0, 2.0, 3.0], resolution: 24}
colluvium: {yield: 0.2, talus_angle: 30}
bubbles:
  - {up_to: 0.5, bubble: {sphere: {radius: 0.3}}}
  - {up_to: 1.0, bubble: {sphere: {radius: 0.2}}, cavernous: 0.5}
export: [ply, obj, glb]
time: 0.5
render: {width: 320, height: 240}
)";

TEST(PresetExtends, MapsDeepMergeListsAndScalarsAreReplaced) {
  TempDir dir;
  writeText(dir.path() / "base.yaml", kBase);
  writeText(dir.path() / "child.yaml",
            "extends: base.yaml\nname: child\nshape: {box: {size: [1, 1, 1]}}\n"
            "colluvium: {yield: 0.4}\nbubbles: [{up_to: 1, bubble: {sphere: {radius: 0.25}}}]\n"
            "export: [vdb]\ntime: 0.25\n");
  const Preset p = loadPreset(dir.path() / "child.yaml");
  EXPECT_EQ(p.name, "child");
  EXPECT_EQ(p.colluvium.yield, 0.4);         // the child's key wins
  EXPECT_EQ(p.colluvium.talus_angle, 30.0);  // its base sibling stays
  EXPECT_EQ(p.grid.size, (Vec3d{2.0, 2.0, 3.0}));
  EXPECT_EQ(p.grid.resolution, 24);
  EXPECT_EQ(p.render.width, 320);
  // Lists are replaced whole, not merged item by item.
  EXPECT_EQ(p.exports, std::vector<std::string>{"vdb"});
  ASSERT_EQ(p.bubbles.size(), 1u);
  EXPECT_EQ(p.bubbles[0].bubble.extents[0], 0.25);
  EXPECT_EQ(p.bubbles[0].cavernous, 0.0);
  EXPECT_EQ(*p.stop.time, 0.25);
  EXPECT_EQ(p.sources, (std::vector<fs::path>{dir.path() / "child.yaml", dir.path() / "base.yaml"}));
}

// Choosing one of a set of alternatives drops the base's choice instead of merging in beside it.
TEST(PresetExtends, ChoosingAnAlternativeReplacesTheBasesChoice) {
  TempDir dir;
  writeText(dir.path() / "base.yaml",
            "rockbake: 1\ntime: 1\nshape: {box: {size: [1, 1, 1]}, center: [1, 1, 0]}\nresponse: {threshold: 0.5}\n"
            "durability:\n  points: [[0, 1], [0.5, 2], [1, 1]]\n  noise: [null, {amplitude: 0.2}]\n");
  writeText(dir.path() / "child.yaml",
            "extends: base.yaml\nname: c\ncycles: 4\nshape: {sphere: {radius: 0.5}}\nresponse: {power: 2}\n"
            "durability: {points: [[0, 3], [1, 3]]}\n");
  const Preset p = loadPreset(dir.path() / "child.yaml");
  EXPECT_EQ(*p.stop.cycles, 4);
  EXPECT_FALSE(p.stop.time.has_value());
  ASSERT_TRUE(std::holds_alternative<SphereShape>(p.shape.kind));
  EXPECT_EQ(*p.shape.center, (Vec3d{1, 1, 0}));  // beside the kind: still inherited
  EXPECT_EQ(p.response.kind, ResponseParams::Kind::Power);
  EXPECT_EQ(p.durability.graph.points.size(), 2u);
  EXPECT_TRUE(p.durability.graph.noise.empty());  // the base's noise was for its own three points

  // Noise alone keeps the base's points.
  writeText(dir.path() / "child.yaml", "extends: base.yaml\nname: c\ndurability: {noise: [{amplitude: 0.1}, null]}\n");
  const Preset noisy = loadPreset(dir.path() / "child.yaml");
  EXPECT_EQ(noisy.durability.graph.points.size(), 3u);
  ASSERT_EQ(noisy.durability.graph.noise.size(), 2u);
  EXPECT_EQ(noisy.durability.graph.noise[0]->amplitude, 0.1);
  EXPECT_EQ(*noisy.stop.time, 1.0);
}

TEST(PresetExtends, AnExtendedPresetResolvesLikeItsFlatCopy) {
  TempDir dir;
  writeText(dir.path() / "base.yaml", kBase);
  writeText(dir.path() / "child.yaml", "extends: base.yaml\nname: child\nshape: {sphere: {radius: 0.8}}\n");
  writeText(dir.path() / "flat.yaml", std::string(kBase) + "name: child\nshape: {sphere: {radius: 0.8}}\n");
  const Preset extended = loadPreset(dir.path() / "child.yaml");
  const Preset flat = loadPreset(dir.path() / "flat.yaml");
  EXPECT_EQ(presetToJson(extended), presetToJson(flat));
  EXPECT_EQ(presetToJson(extended).dump(), presetToJson(flat).dump());
  EXPECT_FALSE(presetToJson(extended).contains("extends"));
  EXPECT_EQ(flat.sources, std::vector<fs::path>{dir.path() / "flat.yaml"});
}

TEST(PresetExtends, ChainsOfBasesInOtherFolders) {
  TempDir dir;
  // Each extends is relative to the file that says it.
  writeText(dir.path() / "shared" / "common" / "rock.yaml",
            "rockbake: 1\ntime: 1\nseed: 1\ncolluvium: {yield: 0.1, talus_angle: 20, removal: 0.3}\n");
  writeText(dir.path() / "shared" / "house.yaml", "extends: common/rock.yaml\nseed: 5\ncolluvium: {talus_angle: 40}\n");
  writeText(dir.path() / "presets" / "a.yaml",
            "extends: ../shared/house.yaml\nname: a\nshape: {box: {size: [1, 1, 1]}}\ncolluvium: {removal: 0}\n");
  const Preset p = loadPreset(dir.path() / "presets" / "a.yaml");
  EXPECT_EQ(p.colluvium.yield, 0.1);
  EXPECT_EQ(p.colluvium.talus_angle, 40.0);
  EXPECT_EQ(p.colluvium.removal, 0.0);
  EXPECT_EQ(p.seed, 5u);
  EXPECT_EQ(*p.stop.time, 1.0);
  EXPECT_EQ(p.sources, (std::vector<fs::path>{dir.path() / "presets" / "a.yaml", dir.path() / "shared" / "house.yaml",
                                              dir.path() / "shared" / "common" / "rock.yaml"}));
}

TEST(PresetExtends, CyclesAreReportedWithTheChain) {
  TempDir dir;
  writeText(dir.path() / "a.yaml", "extends: b.yaml\nname: a\n");
  writeText(dir.path() / "b.yaml", "rockbake: 1\nextends: a.yaml\n");
  const std::string cycle = loadError(dir.path() / "a.yaml");
  EXPECT_NE(cycle.find((dir.path() / "b.yaml").string() +
                       ":2:10: extends: the base presets form a cycle: a.yaml → b.yaml → a.yaml"),
            std::string::npos)
      << cycle;
  writeText(dir.path() / "self.yaml", "rockbake: 1\nextends: ./self.yaml\n");
  EXPECT_NE(loadError(dir.path() / "self.yaml").find("form a cycle: self.yaml → self.yaml"), std::string::npos);

  const auto bake = runRockbake({"bake", (dir.path() / "a.yaml").string(), "-o", (dir.path() / "out").string()});
  EXPECT_EQ(bake.exit_status, 2) << bake.output;
  EXPECT_NE(bake.output.find("a.yaml → b.yaml → a.yaml"), std::string::npos) << bake.output;
  const auto lint = runRockbake({"lint", (dir.path() / "a.yaml").string()});
  EXPECT_EQ(lint.exit_status, 2) << lint.output;
  EXPECT_NE(lint.output.find("a.yaml → b.yaml → a.yaml"), std::string::npos) << lint.output;
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

TEST(PresetExtends, UnusableBasesAreReportedAtTheExtendsKey) {
  TempDir dir;
  const fs::path child = dir.path() / "child.yaml";
  const std::string at = child.string() + ":1:10: extends: ";
  writeText(child, "extends: nowhere.yaml\nname: c\n");
  const std::string missing = loadError(child);
  EXPECT_NE(missing.find(at + "no base preset at " + (dir.path() / "nowhere.yaml").string()), std::string::npos)
      << missing;

  writeText(child, "extends: list.yaml\nname: c\n");
  writeText(dir.path() / "list.yaml", "- rockbake: 1\n");
  const std::string list = loadError(child);
  EXPECT_NE(list.find(at + "the base preset " + (dir.path() / "list.yaml").string() + " is not a YAML map"),
            std::string::npos)
      << list;

  // Malformed YAML: at the extends key, quoting the base's own position.
  writeText(child, "extends: broken.yaml\nname: c\n");
  writeText(dir.path() / "broken.yaml", "rockbake: 1\ntime: [1, 2\n");
  const std::string broken = loadError(child);
  EXPECT_NE(broken.find(at + "cannot use the base preset: " + (dir.path() / "broken.yaml").string() + ":3:"),
            std::string::npos)
      << broken;
  EXPECT_NE(broken.find("malformed YAML"), std::string::npos) << broken;

  writeText(child, "extends: [a.yaml, b.yaml]\nname: c\n");
  EXPECT_NE(loadError(child).find(at + "expected the path of a base preset, found a list"), std::string::npos)
      << loadError(child);
}

TEST(PresetExtends, ProblemsInABaseAreLocatedInTheBase) {
  TempDir dir;
  const fs::path base = dir.path() / "base.yaml";
  const fs::path child = dir.path() / "child.yaml";
  writeText(child, "extends: base.yaml\nname: c\nshape: {box: {size: [1, 1, 1]}}\n");
  writeText(base, "rockbake: 1\ntime: 1\ncolluvium: {yield: 1.5}\n");
  EXPECT_NE(loadError(child).find(base.string() + ":3:20: colluvium.yield: must be in [0, 1], found 1.5"),
            std::string::npos)
      << loadError(child);

  writeText(base, "rockbake: 1\ntime: 1\nmesh:\n  smoothing: 1\n  subdivison: 1\n");
  EXPECT_NE(loadError(child).find(base.string() +
                                  ":5:3: mesh.subdivison: unknown key 'subdivison'; did you mean 'subdivision'?"),
            std::string::npos)
      << loadError(child);

  // A key the child gives inside a map the base started is the child's.
  writeText(base, "rockbake: 1\ntime: 1\ncolluvium: {yield: 0.5}\n");
  writeText(child, "extends: base.yaml\nname: c\nshape: {box: {size: [1, 1, 1]}}\ncolluvium: {talus_angle: 95}\n");
  EXPECT_NE(loadError(child).find(child.string() + ":4:26: colluvium.talus_angle: must be in (0, 90)"),
            std::string::npos)
      << loadError(child);

  // Repeated keys in a base are caught even though the merge reads it key by key.
  writeText(base, "rockbake: 1\ntime: 1\ncolluvium: {yield: 0.5}\ncolluvium: {yield: 0.7}\n");
  EXPECT_NE(loadError(child).find(base.string() + ":4:1: colluvium: 'colluvium' is given twice (first on line 3)"),
            std::string::npos)
      << loadError(child);
}

TEST(PresetExtends, RelativePathsResolveAgainstTheFolderOfTheFileThatGivesThem) {
  TempDir dir;
  writeText(dir.path() / "house" / "shapes" / "s.png", "only its existence is checked here");
  writeText(dir.path() / "house" / "base.yaml",
            "rockbake: 1\ntime: 1\nshape:\n  image: {path: shapes/s.png, mode: revolve, height: 2}\n");
  writeText(dir.path() / "child.yaml", "extends: house/base.yaml\nname: c\nshape: {image: {height: 3}}\n");
  const Preset p = loadPreset(dir.path() / "child.yaml");
  const auto& image = std::get<ImageShape>(p.shape.kind);
  EXPECT_EQ(image.path, dir.path() / "house" / "shapes" / "s.png");
  EXPECT_EQ(image.height, 3.0);
  EXPECT_EQ(image.mode, ImageMode::Revolve);

  // A path the child writes is the child's: relative to the child's folder.
  writeText(dir.path() / "shapes" / "own.png", "only its existence is checked here");
  writeText(dir.path() / "child.yaml", "extends: house/base.yaml\nname: c\nshape: {image: {path: shapes/own.png}}\n");
  EXPECT_EQ(std::get<ImageShape>(loadPreset(dir.path() / "child.yaml").shape.kind).path,
            dir.path() / "shapes" / "own.png");

  // A missing file in the base: located there, and the hint says which folder counts.
  writeText(dir.path() / "house" / "base.yaml", "rockbake: 1\ntime: 1\nshape:\n  image: {path: gone.png, height: 2}\n");
  writeText(dir.path() / "child.yaml", "extends: house/base.yaml\nname: c\n");
  const std::string missing = loadError(dir.path() / "child.yaml");
  EXPECT_NE(missing.find((dir.path() / "house" / "base.yaml").string() + ":4:17: shape.image.path: no image file at " +
                         (dir.path() / "house" / "gone.png").string()),
            std::string::npos)
      << missing;
  EXPECT_NE(missing.find("paths are relative to the folder of " + (dir.path() / "house" / "base.yaml").string()),
            std::string::npos)
      << missing;
}

TEST(PresetExtends, OverridesApplyToTheMergedPreset) {
  TempDir dir;
  writeText(dir.path() / "base.yaml", kBase);
  writeText(dir.path() / "child.yaml", "extends: base.yaml\nname: child\nshape: {box: {size: [1, 1, 1]}}\n");
  PresetOverrides o;
  o.sets = {"colluvium.yield=0.6", "bubbles.1.cavernous=0.9"};
  o.resolution = 16;
  const Preset p = loadPreset(dir.path() / "child.yaml", o);
  EXPECT_EQ(p.colluvium.yield, 0.6);
  EXPECT_EQ(p.colluvium.talus_angle, 30.0);
  EXPECT_EQ(p.bubbles[1].cavernous, 0.9);  // an index into the base's list
  EXPECT_EQ(p.grid.resolution, 16);
  EXPECT_EQ(p.grid.size[2], 3.0);

  PresetOverrides bad;
  bad.sets = {"colluvium.talus_angle=91"};
  EXPECT_NE(loadError(dir.path() / "child.yaml", bad)
                .find("--set colluvium.talus_angle=91: colluvium.talus_angle: must be in (0, 90)"),
            std::string::npos);
  PresetOverrides extends;
  extends.sets = {"extends=other.yaml"};
  EXPECT_NE(loadError(dir.path() / "child.yaml", extends).find("extends: extends cannot be overridden"),
            std::string::npos);
}

TEST(PresetOverrides, SetOriginsNameWhereEachOverrideCameFrom) {
  TempDir dir;
  writeText(dir.path() / "p.yaml", "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n");
  PresetOverrides o;
  o.sets = {"colluvium.yield=3"};
  o.set_origins = {"lib.yaml:12:9 (wedge 'tall')"};
  EXPECT_NE(loadError(dir.path() / "p.yaml", o)
                .find("lib.yaml:12:9 (wedge 'tall'): colluvium.yield: must be in [0, 1], found 3"),
            std::string::npos)
      << loadError(dir.path() / "p.yaml", o);
  o.sets = {"colluvium.yield"};
  EXPECT_NE(loadError(dir.path() / "p.yaml", o)
                .find("lib.yaml:12:9 (wedge 'tall'): 'colluvium.yield': expected key.path=VALUE"),
            std::string::npos)
      << loadError(dir.path() / "p.yaml", o);
  // Entries past the end (or empty) fall back to naming the flag.
  o.sets = {"colluvium.yield=0.5", "mesh.subdivision=9"};
  EXPECT_NE(loadError(dir.path() / "p.yaml", o).find("--set mesh.subdivision=9: mesh.subdivision"), std::string::npos)
      << loadError(dir.path() / "p.yaml", o);
  o.set_origins = {"", ""};
  EXPECT_NE(loadError(dir.path() / "p.yaml", o).find("--set mesh.subdivision=9: mesh.subdivision"), std::string::npos);
  // The origin also covers a key the override created on its way.
  o.sets = {"colluvum.yield=0.3"};
  o.set_origins = {"lib.yaml:3:5 (wedge 'soft')"};
  EXPECT_NE(loadError(dir.path() / "p.yaml", o)
                .find("lib.yaml:3:5 (wedge 'soft'): colluvum: unknown key 'colluvum'; did you mean 'colluvium'?"),
            std::string::npos)
      << loadError(dir.path() / "p.yaml", o);
}

// ---- lint ----

TEST(PresetLint, ListsEveryProblemWithItsLocation) {
  TempDir dir;
  const fs::path preset = dir.path() / "p.yaml";
  const fs::path base = dir.path() / "base.yaml";
  writeText(base,
            "rockbake: 1\ntime: 1\nbubbles:\n  - up_to: 1\n"
            "    bubble: {sphere: {radius: -0.2}}\n");
  writeText(preset,
            "extends: base.yaml\n"
            "name: p\n"
            "shape: {box: {size: [1, 1, 1]}}\n"
            "grid: {size: [2, 2, 2], resolution: high}\n"
            "colluvium: {yeild: 0.3}\n"
            "mesh: {subdivision: 7}\n"
            "respnse: {power: 2}\n");
  const std::string p = preset.string(), b = base.string();
  EXPECT_EQ(lintLocations(preset), (std::vector<std::string>{p + ":4:37: grid.resolution", p + ":5:13: colluvium.yeild",
                                                             p + ":6:21: mesh.subdivision", p + ":7:1: respnse",
                                                             b + ":5:31: bubbles.0.bubble.sphere.radius"}));
  // Loading stops at the first.
  EXPECT_NE(loadError(preset).find(p + ":7:1: respnse: unknown key"), std::string::npos);

  const auto result = runRockbake({"lint", p});
  EXPECT_EQ(result.exit_status, 2) << result.output;
  for (const std::string& line :
       {p + ":4:37: grid.resolution: expected a whole number, found 'high'",
        p + ":5:13: colluvium.yeild: unknown key 'yeild'; did you mean 'yield'? (valid keys here: yield, "
            "talus_angle, removal)",
        p + ":6:21: mesh.subdivision: must be a whole number from 0 to 3, found 7",
        p + ":7:1: respnse: unknown key 'respnse'; did you mean 'response'?",
        b + ":5:31: bubbles.0.bubble.sphere.radius: must be greater than 0, found -0.2"})
    EXPECT_NE(result.output.find(line), std::string::npos) << line << "\n" << result.output;
  EXPECT_EQ(result.output.find(": ok"), std::string::npos) << result.output;
}

TEST(PresetLint, EveryUnknownKeyOfAMapIsListed) {
  TempDir dir;
  const fs::path preset = dir.path() / "p.yaml";
  writeText(preset,
            "rockbake: 1\nnmae: p\nshape: {box: {size: [1, 1, 1]}, centre: [0, 0, 0]}\ntime: 1\n"
            "rockfal: {mode: drop}\n");
  const std::string p = preset.string();
  EXPECT_EQ(lintLocations(preset),
            (std::vector<std::string>{p + ":1:1: ", p + ":2:1: nmae", p + ":3:33: shape.centre", p + ":5:1: rockfal"}));
  EXPECT_NE(lintPreset(preset)[0].problem().find("missing 'name'"), std::string::npos);
  EXPECT_NE(lintPreset(preset)[2].problem().find("did you mean 'center'?"), std::string::npos);
}

TEST(PresetLint, APartialBaseAloneIsNotAPreset) {
  TempDir dir;
  writeText(dir.path() / "base.yaml", kBase);
  const std::string b = (dir.path() / "base.yaml").string();
  EXPECT_EQ(lintLocations(dir.path() / "base.yaml"), (std::vector<std::string>{b + ":1:1: ", b + ":1:1: "}));
  std::string problems;
  for (const auto& problem : lintPreset(dir.path() / "base.yaml")) problems += problem.problem() + "\n";
  EXPECT_NE(problems.find("missing 'name'"), std::string::npos) << problems;
  EXPECT_NE(problems.find("missing 'shape'"), std::string::npos) << problems;
}

TEST(PresetLint, CleanPresetsSayOkAndExitZero) {
  TempDir dir;
  writeText(dir.path() / "base.yaml", kBase);
  writeText(dir.path() / "good.yaml", "extends: base.yaml\nname: good\nshape: {box: {size: [1, 1, 1]}}\n");
  writeText(dir.path() / "bad.yaml", "extends: base.yaml\nname: bad\nshape: {box: {size: [1, 1, -1]}}\n");
  EXPECT_TRUE(lintPreset(dir.path() / "good.yaml").empty());
  const auto good = runRockbake({"lint", (dir.path() / "good.yaml").string()});
  EXPECT_EQ(good.exit_status, 0) << good.output;
  EXPECT_EQ(good.output, (dir.path() / "good.yaml").string() + ": ok\n");

  // Every file is checked; one bad file makes the run fail.
  const auto mixed = runRockbake({"lint", (dir.path() / "bad.yaml").string(), (dir.path() / "good.yaml").string(),
                                  (dir.path() / "missing.yaml").string()});
  EXPECT_EQ(mixed.exit_status, 2) << mixed.output;
  EXPECT_NE(mixed.output.find((dir.path() / "bad.yaml").string() + ":3:28: shape.box.size.2: must be greater than 0"),
            std::string::npos)
      << mixed.output;
  EXPECT_NE(mixed.output.find((dir.path() / "good.yaml").string() + ": ok"), std::string::npos) << mixed.output;
  EXPECT_NE(mixed.output.find((dir.path() / "missing.yaml").string() + ": cannot read the preset file"),
            std::string::npos)
      << mixed.output;
  EXPECT_NE(mixed.output.find("2 problems in 2 of 3 files"), std::string::npos) << mixed.output;
}

// `rockbake lint presets/*.yaml`, the first thing anyone types: base.yaml is linted as a base (a
// partial house style other presets extend) and library.yaml as a library, each saying so.
TEST(PresetLint, EveryShippedFileIsClean) {
  std::vector<std::string> args = {"lint"};
  for (const auto& entry : fs::directory_iterator(test::sourceDir() / "presets"))
    if (entry.path().extension() == ".yaml") args.push_back(entry.path().string());
  ASSERT_GE(args.size(), 2u);
  const auto result = runRockbake(args);
  EXPECT_EQ(result.exit_status, 0) << result.output;
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string name = fs::path(args[i]).filename().string();
    const std::string ok = args[i] + (name == "base.yaml"      ? ": ok (a base"
                                      : name == "library.yaml" ? ": ok (a library of 33 jobs"
                                                               : ": ok\n");
    EXPECT_NE(result.output.find(ok), std::string::npos) << args[i] << "\n" << result.output;
  }
}

TEST(PresetLint, ABasesProblemsAreFoundInTheBase) {
  TempDir dir;
  writeText(dir.path() / "house.yaml", "rockbake: 1\ncolluvium: {yeild: 0.5}\nmesh: {subdivision: 9}\n");
  const auto result = runRockbake({"lint", (dir.path() / "house.yaml").string()});
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("house.yaml:2:13: colluvium.yeild: unknown key 'yeild'; did you mean 'yield'?"),
            std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("house.yaml:3:21: mesh.subdivision:"), std::string::npos) << result.output;
}

TEST(PresetLint, ALibraryIsLintedWithEveryJobsPresetAndWedge) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", test::kSmallPreset);
  writeText(dir.path() / "lib.yaml",
            "- preset: small.yaml\n  seeds: [1, 2]\n  wedges:\n    - {name: ok}\n"
            "    - {name: wild, set: {colluvium.yield: 3}}\n");
  const auto result = runRockbake({"lint", (dir.path() / "lib.yaml").string()});
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("lib.yaml:5:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("colluvium.yield: must be in [0, 1]"), std::string::npos) << result.output;
  // --set reaches every preset, and the library's own jobs are counted.
  writeText(dir.path() / "lib.yaml", "- preset: small.yaml\n  seeds: [1, 2]\n");
  const auto clean = runRockbake({"lint", (dir.path() / "lib.yaml").string()});
  EXPECT_EQ(clean.exit_status, 0) << clean.output;
  EXPECT_NE(clean.output.find("lib.yaml: ok (a library of 2 jobs"), std::string::npos) << clean.output;
  const auto set = runRockbake({"lint", (dir.path() / "lib.yaml").string(), "--set", "time=-1"});
  EXPECT_EQ(set.exit_status, 2) << set.output;
  EXPECT_NE(set.output.find("--set time=-1: time:"), std::string::npos) << set.output;
}

TEST(PresetLint, BakingALibraryFileSaysHowToBakeOne) {
  const auto result = runRockbake({"bake", (test::sourceDir() / "presets" / "library.yaml").string(), "-o",
                                   (fs::temp_directory_path() / "rockbake-never-written").string()});
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_NE(result.output.find("library.yaml:1:1: this is a library file"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("rockbake library"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(fs::temp_directory_path() / "rockbake-never-written"));
}

// ---- preset show ----

TEST(PresetShow, PrintsTheResolvedPresetWithDefaultsExtendsAndOverrides) {
  TempDir dir;
  writeText(dir.path() / "base.yaml", kBase);
  const fs::path child = dir.path() / "child.yaml";
  writeText(child, "extends: base.yaml\nname: child\nshape: {box: {size: [1, 1, 1]}}\ncolluvium: {yield: 0.4}\n");
  const auto result = runRockbake(
      {"preset", "show", child.string(), "--set", "colluvium.removal=0.25", "--seed", "11", "--resolution", "20"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const nlohmann::json shown = nlohmann::json::parse(result.output);
  EXPECT_EQ(shown["name"], "child");
  EXPECT_EQ(shown["mesh"]["subdivision"], 2);  // a default the preset does not mention
  EXPECT_EQ(shown["render"]["quality"], 9);
  EXPECT_EQ(shown["colluvium"]["yield"], 0.4);         // the child
  EXPECT_EQ(shown["colluvium"]["talus_angle"], 30.0);  // the base
  EXPECT_EQ(shown["colluvium"]["removal"], 0.25);      // --set
  EXPECT_EQ(shown["seed"], 11);
  EXPECT_EQ(shown["grid"]["resolution"], 20);
  EXPECT_EQ(shown["grid"]["size"][2], 3.0);
  EXPECT_EQ(shown["export"], nlohmann::json::parse(R"(["ply", "obj", "glb"])"));
  // Exactly what a bake embeds in stats.json.
  PresetOverrides o;
  o.sets = {"colluvium.removal=0.25"};
  o.seed = 11;
  o.resolution = 20;
  EXPECT_EQ(shown, presetToJson(loadPreset(child, o)));

  const auto bad = runRockbake({"preset", "show", child.string(), "--set", "colluvium.yield=2"});
  EXPECT_EQ(bad.exit_status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--set colluvium.yield=2: colluvium.yield: must be in [0, 1]"), std::string::npos)
      << bad.output;
  EXPECT_EQ(runRockbake({"preset"}).exit_status, 2);
  EXPECT_EQ(runRockbake({"preset", "show"}).exit_status, 2);
}

}  // namespace
}  // namespace rockbake
