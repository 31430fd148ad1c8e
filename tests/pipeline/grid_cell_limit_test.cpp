// A grid over the simulation's cell limit (sim/grid_layout.h: 2³² − 1 cells) is
// refused at grid.resolution, on every machine and before the memory guard, with
// the highest resolution that fits; through the executable, exit 2 and nothing written.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "pipeline/read_inputs.h"
#include "preset/load_preset.h"
#include "sim/grid_layout.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using test::runRockbake;
using test::TempDir;

// A free cube, valid as a preset at any resolution (its bubble spans 48 voxels at 2048).
const char* const kCube =
    "rockbake: 1\nname: cube\nshape: {box: {size: [1.5, 1.5, 1.5]}}\ntime: 0.1\n"
    "grid: {size: [2, 2, 2], resolution: 2048, ground: false}\n"
    "bubbles: [{up_to: 1, bubble: {sphere: {radius: 0.04}}}]\n";

TEST(GridCellLimit, RefusedAtResolutionWithTheHighestThatFits) {
  const Preset huge = parsePreset(kCube, "dir/cube.yaml");
  ASSERT_GT(computeGridLayout(huge).cellCount(), kMaxSimulationCells);
  const int fits = largestResolutionWithinCellLimit(huge);
  try {
    checkGridCellCount(huge);
    FAIL() << "a grid of " << computeGridLayout(huge).cellCount() << " cells was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.keyPath(), "grid.resolution");
    EXPECT_NE(message.find("dir/cube.yaml:5:"), std::string::npos) << message;
    EXPECT_NE(message.find(std::to_string(computeGridLayout(huge).cellCount()) + " cells"), std::string::npos)
        << message;
    EXPECT_NE(message.find("at most 4294967295 (2^32 - 1)"), std::string::npos) << message;
    EXPECT_NE(message.find("lower grid.resolution (or --resolution) to " + std::to_string(fits) + " or less"),
              std::string::npos)
        << message;
  }
  // What it names passes; the cell check is the same on every machine, so it runs before the memory guard.
  Preset lower = huge;
  lower.grid.resolution = fits;
  EXPECT_NO_THROW(checkGridCellCount(lower));
  try {
    readInputs(huge);
    FAIL() << "readInputs accepted the grid";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("2^32 - 1"), std::string::npos) << e.what();
  }
}

// Through the executable: lint lists it at the preset's key, bake at the flag that set it, exit 2, nothing written.
TEST(GridCellLimit, TheExecutableRefusesItWithExit2AndWritesNothing) {
  TempDir dir;
  test::writeText(dir.path() / "cube.yaml", kCube);
  const auto lint = runRockbake({"lint", (dir.path() / "cube.yaml").string()});
  EXPECT_EQ(lint.exit_status, 2) << lint.output;
  EXPECT_NE(lint.output.find("cube.yaml:5:"), std::string::npos) << lint.output;
  EXPECT_NE(lint.output.find("grid.resolution: a "), std::string::npos) << lint.output;

  std::string preview = kCube;
  preview.replace(preview.find("resolution: 2048"), 16, "resolution: 48");
  test::writeText(dir.path() / "preview.yaml", preview);
  const fs::path out = dir.path() / "out";
  const auto bake =
      runRockbake({"bake", (dir.path() / "preview.yaml").string(), "--resolution", "2048", "-o", out.string()});
  EXPECT_EQ(bake.exit_status, 2) << bake.output;
  EXPECT_NE(bake.output.find("--resolution 2048"), std::string::npos) << bake.output;
  EXPECT_NE(bake.output.find("2^32 - 1"), std::string::npos) << bake.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace rockbake
