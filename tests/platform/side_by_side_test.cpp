#include "platform/side_by_side.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace rockbake {
namespace {

using namespace std::chrono_literals;

// A parallel loop whose iterations wait for the other job to throw (a second at most), then count
// themselves slowly, so that cancelling the loop then would leave iterations uncounted.
void countSlowly(std::atomic<int>& counted, std::atomic<bool>& started, const std::atomic<bool>& thrown) {
  tbb::parallel_for(0, 400, [&](int) {
    started = true;
    for (int i = 0; i < 1000 && !thrown; ++i) std::this_thread::sleep_for(1ms);
    std::this_thread::sleep_for(100us);
    ++counted;
  });
}

// The first job throws while the second's loop runs (or, on one worker, before it starts).
void throwOnceStarted(const std::atomic<bool>& started, std::atomic<bool>& thrown) {
  for (int i = 0; i < 1000 && !started; ++i) std::this_thread::sleep_for(1ms);
  thrown = true;
  throw std::runtime_error("first");
}

TEST(SideBySide, AnExceptionInOneJobLeavesTheOthersLoopsWhole) {
  tbb::global_control workers(tbb::global_control::max_allowed_parallelism, 2);
  std::atomic<int> counted{0};
  std::atomic<bool> started{false}, thrown{false};
  try {
    sideBySide([&] { throwOnceStarted(started, thrown); }, [&] { countSlowly(counted, started, thrown); });
    FAIL() << "the first job's exception was not rethrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "first");
  }
  EXPECT_EQ(counted.load(), 400);  // tbb::parallel_invoke would have cancelled the loop
}

TEST(SideBySide, TheFirstJobsExceptionWinsWhenBothThrow) {
  for (int round = 0; round < 20; ++round) {
    try {
      sideBySide([] { throw std::runtime_error("first"); }, [] { throw std::logic_error("second"); });
      FAIL();
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "first");
    } catch (const std::logic_error&) {
      FAIL() << "the second job's exception came out";
    }
  }
}

TEST(SideBySide, BothJobsRunToTheirEnd) {
  int a = 0, b = 0;
  sideBySide([&] { a = 1; }, [&] { b = 2; });
  EXPECT_EQ(a + b, 3);
}

TEST(AllSideBySide, EveryJobRunsAndTheLowestNumberedExceptionComesOut) {
  for (int round = 0; round < 20; ++round) {
    std::vector<std::atomic<int>> ran(16);
    try {
      allSideBySide(ran.size(), [&](std::size_t i) {
        ++ran[i];
        if (i == 5 || i == 11) throw std::runtime_error(std::to_string(i));
      });
      FAIL() << "no exception came out";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "5");
    }
    for (const auto& r : ran) EXPECT_EQ(r.load(), 1);
  }
}

}  // namespace
}  // namespace rockbake
