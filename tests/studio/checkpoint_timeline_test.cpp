// The studio's checkpoints stay bounded in count and bytes however far the
// timeline runs (studio/checkpoint_timeline.h), and a seek never re-simulates
// more than the spacing.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "core/error.h"
#include "studio/checkpoint_timeline.h"
#include "studio/studio_session.h"
#include "test_support.h"

namespace rockbake {
namespace {

SimulationSnapshot snapshotAt(int cycle, std::size_t bytes = 1000) {
  SimulationSnapshot s;
  s.cycle = cycle;
  s.rock.material.assign(bytes, Material::Air);
  return s;
}

// What a run of `cycles` keeps, offering every cycle as the studio does.
CheckpointTimeline runFor(int cycles, CheckpointBounds bounds, int spacing = 1, std::size_t bytes = 1000) {
  CheckpointTimeline timeline(bounds);
  timeline.restart(snapshotAt(0, bytes), spacing);
  for (int c = 1; c <= cycles; ++c)
    if (timeline.wants(c)) timeline.keep(snapshotAt(c, bytes));
  return timeline;
}

TEST(CheckpointTimeline, TenThousandCyclesKeepAtMostTheCount) {
  const CheckpointTimeline timeline = runFor(10000, {32, std::size_t(1) << 30});
  const std::vector<int> cycles = timeline.cycles();
  EXPECT_LE(cycles.size(), 32u);
  EXPECT_GE(cycles.size(), 16u) << "thinning halves, no more";
  EXPECT_EQ(cycles.front(), 0);
  EXPECT_GT(cycles.back(), 10000 - timeline.spacing()) << "the latest stays within one spacing of the end";
  for (const int c : cycles) EXPECT_EQ(c % timeline.spacing(), 0) << c;
  // Every cycle has a checkpoint at most a spacing behind it.
  for (int c = 0; c <= 10000; c += 37) EXPECT_GT(timeline.atOrBefore(c).cycle, c - timeline.spacing()) << c;
}

TEST(CheckpointTimeline, BytesAreBoundedTooAndOneHugeStartStays) {
  const CheckpointTimeline timeline = runFor(500, {1000, 20'000}, 1, 1000);
  EXPECT_LE(timeline.bytes(), 20'000u);
  std::size_t counted = 0;
  for (const int c : timeline.cycles()) counted += snapshotBytes(timeline.atOrBefore(c));
  EXPECT_EQ(counted, timeline.bytes());
  const CheckpointTimeline huge = runFor(50, {32, 100}, 1, 1000);
  EXPECT_EQ(huge.cycles(), std::vector<int>{0}) << "cycle 0's alone, larger than the bound";
}

TEST(CheckpointTimeline, RestartAndDropAfterFreeCheckpoints) {
  CheckpointTimeline timeline = runFor(100, {8, std::size_t(1) << 30});
  const int spacing = timeline.spacing();
  EXPECT_GT(spacing, 1);
  timeline.dropAfter(spacing);
  EXPECT_EQ(timeline.cycles(), (std::vector<int>{0, spacing}));
  EXPECT_FALSE(timeline.wants(spacing)) << "already there";
  EXPECT_TRUE(timeline.wants(2 * spacing));
  timeline.restart(snapshotAt(0), 3);
  EXPECT_EQ(timeline.cycles(), std::vector<int>{0});
  EXPECT_EQ(timeline.spacing(), 3);
  EXPECT_EQ(timeline.bytes(), snapshotBytes(snapshotAt(0)));
}

// A preset that is a FIFO, a device or too large is refused before it is read,
// as `rockbake lint` refuses it.
TEST(StudioSession, RefusesAPresetThatIsNotARegularFileWithoutReadingIt) {
  test::TempDir dir;
  const auto fifo = dir.path() / "fifo.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::filesystem::path& file : {fifo, std::filesystem::path("/dev/zero")})
    EXPECT_THROW(StudioSession(file, 24), InputError) << file;
}

}  // namespace
}  // namespace rockbake
