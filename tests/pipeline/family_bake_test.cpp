// A family through the real executable (docs/model.md §12): the draw recorded
// in asset.json and stats.json as `preset show --individual` prints it, and
// the same bytes at one and two threads.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/sha256.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

// kSmallPreset with a joint set and a family that uses every part of the draw.
std::string familyPreset() {
  return std::string(test::kSmallPreset) +
         "durability:\n  joints:\n    - {strike: 30, dip: 80, spacing: 0.6, width: 0.05, factor: 0.5}\n"
         "family: {scale: [0.8, 1.25], stretch: [[0.7, 1.4], [0.7, 1.4], [0.8, 1.2]], tilt: 10,\n"
         "         warp: {bend: 0.2, taper: 0.3, twist: 30}, fracture: {cuts: [1, 2], depth: [0.1, 0.3]}}\n"
         "texture: {size: 256}\n";
}

TEST(FamilyBake, TheDrawIsRecordedAsPresetShowPrintsIt) {
  test::TempDir dir;
  const fs::path preset = dir.path() / "fam.yaml";
  test::writeText(preset, familyPreset());
  for (const char* seed : {"4", "5"}) {
    const auto shown = test::runRockbake({"preset", "show", preset.string(), "--seed", seed, "--individual"});
    ASSERT_EQ(shown.exit_status, 0) << shown.output;
    const auto baked =
        test::runRockbake({"bake", preset.string(), "--seed", seed, "--no-render", "-o", (dir.path() / seed).string()});
    ASSERT_EQ(baked.exit_status, 0) << baked.output;
    const auto asset = nlohmann::json::parse(test::readBytes(dir.path() / seed / "small" / "asset.json"));
    const auto stats = nlohmann::json::parse(test::readBytes(dir.path() / seed / "small" / "stats.json"));
    const auto individual = nlohmann::json::parse(shown.output);
    EXPECT_EQ(asset["individual"], individual) << seed;
    EXPECT_EQ(stats["individual"], individual) << seed;
    EXPECT_GE(individual["cuts"].size(), 1u);
  }
  EXPECT_NE(test::readBytes(dir.path() / "4" / "small" / "asset.json"),
            test::readBytes(dir.path() / "5" / "small" / "asset.json"));
}

TEST(FamilyBake, TheSameBytesAtOneAndTwoThreads) {
  test::TempDir dir;
  const fs::path preset = dir.path() / "fam.yaml";
  test::writeText(preset, familyPreset());
  for (const char* threads : {"1", "2"}) {
    const auto result = test::runRockbake(
        {"bake", preset.string(), "--threads", threads, "--no-render", "-o", (dir.path() / threads).string()});
    ASSERT_EQ(result.exit_status, 0) << result.output;
  }
  std::size_t compared = 0;
  const fs::path one = dir.path() / "1" / "small", two = dir.path() / "2" / "small";
  for (const auto& entry : fs::recursive_directory_iterator(one)) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), one);
    if (relative == "stats.json" || relative == "manifest.json") continue;  // timings
    EXPECT_EQ(test::readBytes(entry.path()), test::readBytes(two / relative)) << relative;
    ++compared;
  }
  EXPECT_GE(compared, 10u);  // meshes, LODs, maps, rock.vdb, asset.json
}

// A preset without a family bakes as it did before families existed: the rock.vdb of the small box
// and of corner-cavern (a paper figure, which keeps no family) at 24, as the build before families
// wrote them (bench/README.md, "Families", compared every output file of five presets), but for
// rock_sdf, stored as half floats since (docs/formats.md): every other grid of the files is the same,
// and rock_sdf is the earlier float field rounded to halves, value for value.
TEST(FamilyBake, WithoutAFamilyTheBytesAreThoseOfTheBuildBefore) {
  test::TempDir dir;
  test::writeText(dir.path() / "small.yaml", test::kSmallPreset);
  const fs::path out = dir.path() / "out";
  ASSERT_EQ(
      test::runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-mesh"}).exit_status,
      0);
  ASSERT_EQ(test::runRockbake({"bake", (test::sourceDir() / "presets" / "corner-cavern.yaml").string(), "-o",
                               out.string(), "--no-mesh", "--resolution", "24"})
                .exit_status,
            0);
  EXPECT_EQ(sha256Hex(test::readBytes(out / "small" / "rock.vdb")),
            "7b367f0366fc4c6e75f09ce7e379cf3ee90191df8a9469305a4ffc1b2ad5194a");
  EXPECT_EQ(sha256Hex(test::readBytes(out / "corner-cavern" / "rock.vdb")),
            "ad20016f94714cb39b16f870d0408dc8c0d3198ae06805225de0ab74539c0868");
}

}  // namespace
}  // namespace rockbake
