// The phase table (pipeline/bake_phases.h): the progress bar's shares, stats.json's "stages"
// in the table's order, and a bake's progress reports read from it.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/bake_asset.h"
#include "pipeline/bake_phases.h"
#include "test_support.h"

namespace rockbake {
namespace {

TEST(BakePhases, EachPhaseStartsWhereTheOneBeforeEndsAndTheBarEndsAtOne) {
  double end = 0.0;
  for (const BakePhase& p : kBakePhases) {
    EXPECT_GE(p.share, 0.0) << p.name;
    EXPECT_NEAR(p.start, end, 1e-12) << p.name;
    end = p.start + p.share;
  }
  EXPECT_NEAR(end, 1.0, 1e-12);
  EXPECT_EQ(bakeProgress("total"), 1.0);
  EXPECT_THROW(bakeProgress("polish"), std::logic_error);
}

// The positions the studio's bar has always shown, to the bit: start + share · done / of.
TEST(BakePhases, ProgressIsTheStartPlusTheShareDone) {
  for (int planned : {1, 3, 5, 7, 100, 613})
    for (int cycle = 0; cycle <= planned; ++cycle)
      ASSERT_EQ(bakeProgress("simulate", cycle, planned), 0.7 * cycle / planned) << cycle << " of " << planned;
  for (int lods = 1; lods <= 8; ++lods)
    for (int done = 0; done <= lods; ++done) ASSERT_EQ(bakeProgress("texture", done, lods), 0.75 + 0.05 * done / lods);
  EXPECT_EQ(bakeProgress("mesh"), 0.7);
  EXPECT_EQ(bakeProgress("export"), 0.8);
  EXPECT_EQ(bakeProgress("render"), 0.85);
}

TEST(BakePhases, StagesAreWrittenInTheTablesOrderAndOnlyKnownOnes) {
  PhaseTimes times;
  times.add("render", 3.0);
  times.add("load", 1.0);
  times.add("mesh_extract", 0.5);
  times.add("mesh_extract", 0.25);  // summed
  const nlohmann::ordered_json stages = bakeTimingsJson(times);
  std::vector<std::pair<std::string, double>> got;
  for (const auto& [key, value] : stages.items()) got.emplace_back(key, value.get<double>());
  const std::vector<std::pair<std::string, double>> want = {{"load", 1.0}, {"mesh_extract", 0.75}, {"render", 3.0}};
  EXPECT_EQ(got, want);
  times.add("polish", 1.0);
  EXPECT_THROW(bakeTimingsJson(times), std::logic_error);
}

TEST(BakePhases, ABakeReportsProgressUpwardFromTheTableAndEndsDone) {
  test::TempDir dir;
  Preset preset = test::cubePreset(1.0, 24, 0.2);
  preset.name = "cube";
  BakeOptions options;
  options.out_dir = dir.path();
  options.stages.render = false;
  std::vector<std::pair<double, std::string>> reports;
  options.progress = [&](double fraction, const std::string& stage) { reports.emplace_back(fraction, stage); };
  bakeAsset(preset, options);
  ASSERT_GE(reports.size(), 3u);
  for (std::size_t i = 1; i < reports.size(); ++i)
    EXPECT_GE(reports[i].first, reports[i - 1].first) << reports[i].second << " after " << reports[i - 1].second;
  EXPECT_EQ(reports.back(), std::make_pair(1.0, std::string("done")));
  bool meshed = false, exported = false;
  for (const auto& [fraction, stage] : reports) {
    if (stage == "mesh") meshed = fraction == bakeProgress("mesh");
    if (stage == "export") exported = fraction == bakeProgress("export");
    EXPECT_NE(stage, "render");  // off
  }
  EXPECT_TRUE(meshed);
  EXPECT_TRUE(exported);
}

}  // namespace
}  // namespace rockbake
