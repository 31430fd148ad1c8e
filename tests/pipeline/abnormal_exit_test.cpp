// platform/abnormal_exit: when memory runs out where a library cannot unwind
// (OpenVDB's dilation throws again while it unwinds, which ends in
// std::terminate), the process says the registered sentence, removes the
// registered folders and exits 1 instead of aborting. Each case runs in a
// death-test child under an address-space limit.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include "platform/abnormal_exit.h"
#include "platform/openvdb_support.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

#if defined(__SANITIZE_ADDRESS__)
#define SKIP_UNDER_ASAN() GTEST_SKIP() << "AddressSanitizer reserves more address space than a limit allows"
#else
#define SKIP_UNDER_ASAN() (void)0
#endif

// This process's address space now, from /proc (KiB).
std::uint64_t addressSpaceKib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmSize:", 0) == 0) return std::stoull(line.substr(7));
  return 0;
}

void limitAddressSpaceTo(std::uint64_t bytes) {
  const rlimit limit{bytes, bytes};
  ::setrlimit(RLIMIT_AS, &limit);
}

// A folder of this test's own that the death test's child (which runs the test
// again from its start, in the "threadsafe" style) finds at the same path.
fs::path testFolder() {
  const fs::path dir = fs::temp_directory_path() / "rockbake-abnormal-exit" /
                       testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A staging folder as a bake has it: OUT/.<name>.baking-<pid> with a file in it.
fs::path stagingIn(const fs::path& out) {
  const fs::path staging = out / ".rock.baking-1";
  fs::create_directories(staging / "meshes");
  std::ofstream(staging / "meshes" / "lod0.ply") << "ply\n";
  return staging;
}

TEST(AbnormalExitDeathTest, OpenVdbOutOfMemorySaysTheSentenceRemovesTheFolderAndExits1) {
  SKIP_UNDER_ASAN();
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path dir = testFolder();
  const fs::path out = dir / "out";
  const fs::path staging = stagingIn(out);
  // A level-set sphere of radius 200 voxels, 100 voxels either side of its
  // surface: about a gigabyte, built by OpenVDB's own parallel tasks.
  initializeOpenVdb();
  EXPECT_EXIT(
      {
        installAbnormalExitHandler();
        const OnAbnormalExit guard(staging, "out of memory: lower grid.resolution (256 needs about 1 MiB)", true);
        limitAddressSpaceTo((addressSpaceKib() << 10) + (std::uint64_t(160) << 20));
        // Whether OpenVDB ends in std::terminate itself or its std::bad_alloc reaches this noexcept
        // boundary, the end is the same: std::terminate.
        []() noexcept {
          openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(200.f, openvdb::Vec3f(0.f), 1.f, 100.f);
        }();
        std::_Exit(0);  // not reached: the limit is far below what it needs
      },
      testing::ExitedWithCode(1), "^error: out of memory: lower grid.resolution \\(256 needs about 1 MiB\\)\n$");
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_FALSE(fs::exists(out)) << "OUT, created by the bake and left empty, goes too";
  fs::remove_all(dir);
}

TEST(AbnormalExitDeathTest, AnotherExceptionThatCannotUnwindSaysWhatItIs) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path dir = testFolder();
  const fs::path staging = stagingIn(dir / "out");
  std::ofstream(dir / "out" / "kept.txt") << "an earlier asset's file\n";
  EXPECT_EXIT(
      {
        installAbnormalExitHandler();
        const OnAbnormalExit guard(staging, "out of memory: not this", true);
        const auto fail = [] { throw std::runtime_error("the disk is full"); };
        [&]() noexcept { fail(); }();
      },
      testing::ExitedWithCode(1), "^error: the disk is full\n$");
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_TRUE(fs::exists(dir / "out" / "kept.txt")) << "OUT is removed only when left empty";
  fs::remove_all(dir);
}

TEST(AbnormalExitDeathTest, AFolderNoLongerRegisteredIsLeftAlone) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path dir = testFolder();
  const fs::path staging = stagingIn(dir / "out");
  EXPECT_EXIT(
      {
        installAbnormalExitHandler();
        { const OnAbnormalExit committed(staging, "out of memory: renamed into place already"); }
        const auto fail = [] { throw std::bad_alloc(); };
        [&]() noexcept { fail(); }();
      },
      testing::ExitedWithCode(1), "^error: out of memory\n$");
  EXPECT_TRUE(fs::exists(staging / "meshes" / "lod0.ply"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rockbake
