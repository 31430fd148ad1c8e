// The grid's cell limit (sim/grid_layout.h): the simulation numbers cells in 32
// bits, so a grid over 2³² − 1 cells is refused before anything is allocated.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstdlib>
#include <new>
#include <stdexcept>

#include "sim/grid_layout.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

GridLayout layoutOf(int nx, int ny, int nz) {
  GridLayout g;
  g.nx = nx, g.ny = ny, g.nz = nz;
  return g;
}

TEST(GridLayout, TheCellLimitIsTheLast32BitIndexPlusOne) {
  static_assert(kMaxSimulationCells == 4294967295u);
  // 2³² − 1 = 65537 × 65535: the most cells there may be; one more row is too many.
  EXPECT_NO_THROW(requireSimulationCells(layoutOf(65537, 65535, 1)));
  EXPECT_THROW(requireSimulationCells(layoutOf(65536, 65536, 1)), std::invalid_argument);
  EXPECT_THROW(requireSimulationCells(layoutOf(2048, 2048, 2048)), std::invalid_argument);
  EXPECT_NO_THROW(requireSimulationCells(layoutOf(1625, 1625, 1625)));
  try {
    requireSimulationCells(layoutOf(2100, 2100, 1100));
    ADD_FAILURE() << "a 2100×2100×1100 grid was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2100×2100×1100"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("4294967295"), std::string::npos) << e.what();
  }
}

// The highest resolution that fits, margin included: it fits, and one more does not.
TEST(GridLayout, LargestResolutionWithinTheCellLimitIsTight) {
  Preset cube = test::cubePreset(2.0, 2048, 0.05);
  ASSERT_GT(computeGridLayout(cube).cellCount(), kMaxSimulationCells);
  const int largest = largestResolutionWithinCellLimit(cube);
  Preset p = cube;
  p.grid.resolution = largest;
  EXPECT_LE(computeGridLayout(p).cellCount(), kMaxSimulationCells) << largest;
  p.grid.resolution = largest + 1;
  EXPECT_GT(computeGridLayout(p).cellCount(), kMaxSimulationCells) << largest;
  EXPECT_GT(largest, 1500);
  EXPECT_LT(largest, 1625);  // the margin takes its share
  // A grid that fits is its own answer; a flat one fits at a higher resolution.
  p.grid.resolution = 200;
  EXPECT_EQ(largestResolutionWithinCellLimit(p), 200);
  Preset flat = cube;
  flat.grid.size = {2.0, 2.0, 1.0};
  EXPECT_GT(largestResolutionWithinCellLimit(flat), largest);
}

// buildInitialRock and the simulation refuse such a grid before they allocate: run in a child
// whose address space is 1 GiB, a 2048³ grid (8 GiB of materials alone) ends in
// std::invalid_argument, not std::bad_alloc.
TEST(GridLayoutDeathTest, TheSimulationRefusesAnOversizedGridBeforeAllocating) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit allows";
#endif
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const Preset huge = test::cubePreset(2.0, 2048, 0.05);
  const auto refuses = [&](auto&& allocate) {
    const rlimit limit{rlim_t(1) << 30, rlim_t(1) << 30};
    setrlimit(RLIMIT_AS, &limit);
    try {
      allocate();
    } catch (const std::invalid_argument&) {
      std::_Exit(3);
    } catch (const std::bad_alloc&) {
      std::_Exit(4);
    }
    std::_Exit(5);
  };
  EXPECT_EXIT(refuses([&] { buildInitialRock(resolveShape(huge), huge); }), testing::ExitedWithCode(3), "");
  VoxelRock rock;
  rock.layout = computeGridLayout(huge);
  EXPECT_EXIT(refuses([&] { WeatheringSimulation simulation(rock, huge); }), testing::ExitedWithCode(3), "");
}

}  // namespace
}  // namespace rockbake
