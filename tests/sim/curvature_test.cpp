// Bubble counts and calibrated exposure (docs/model.md §3).
#include <gtest/gtest.h>

#include <random>

#include "core/hash.h"
#include "sim/bubble.h"
#include "sim/curvature.h"
#include "test_support.h"

namespace rockbake {
namespace {

// A solid block filling [x0, x1) × [y0, y1) × [z0, z1) of an nx × ny × nz grid.
VoxelRock blockRock(int n, int lo, int hi) {
  VoxelRock rock = test::randomRock(n, n, n, 0, 0.0, false);
  for (int z = lo; z < hi; ++z)
    for (int y = lo; y < hi; ++y)
      for (int x = lo; x < hi; ++x) rock.material[rock.layout.index(x, y, z)] = Material::Rock;
  return rock;
}

struct NamedBubble {
  const char* name;
  Bubble bubble;
};

std::vector<NamedBubble> allBubbleKinds() {
  return {{"sphere r3.4", makeSphereBubble(3.4)},
          {"sphere r6", makeSphereBubble(6.0)},
          {"ellipsoid", makeEllipsoidBubble({5.0, 2.5, 3.2})},
          {"box", makeBoxBubble({3.0, 1.0, 2.5})},
          {"one-voxel sphere", makeSphereBubble(1.0)}};
}

TEST(Bubble, OffsetsAreSymmetricAndContainTheCentre) {
  for (const auto& [name, b] : allBubbleKinds()) {
    std::size_t in_rows = 0;
    for (const auto& r : b.rows) in_rows += std::size_t(r.x_max - r.x_min + 1);
    EXPECT_EQ(in_rows, b.offsets.size()) << name;
  }
  EXPECT_EQ(makeSphereBubble(1.0).offsets.size(), 7u);
  EXPECT_EQ(makeBoxBubble({1, 1, 1}).offsets.size(), 27u);
  // A bubble of the centre alone sees no air on a flat face: it cannot estimate anything.
  EXPECT_THROW(makeSphereBubble(0.6), std::invalid_argument);
  EXPECT_THROW(makeBubbleFromOffsets({{0, 0, 0}, {1, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(makeBubbleFromOffsets({{1, 0, 0}, {-1, 0, 0}}), std::invalid_argument);
}

TEST(Bubble, FlatAlphaMatchesTheSpecsCheckedValue) {
  // docs/model.md §3: a sphere bubble of radius 8 voxels gives alpha_flat ≈ 0.453.
  EXPECT_NEAR(makeSphereBubble(8.0).alpha_flat, 0.453, 0.001);
}

TEST(Bubble, CollectionWeightsAreNormalisedAndNestedCollectionsFlatten) {
  BubbleSpec sphere{BubbleSpec::Kind::Sphere, {0.2, 0, 0}, {}};
  BubbleSpec box{BubbleSpec::Kind::Box, {0.1, 0.1, 0.1}, {}};
  BubbleSpec inner{BubbleSpec::Kind::Collection, {}, {{sphere, 1.0}, {box, 3.0}}};
  BubbleSpec outer{BubbleSpec::Kind::Collection, {}, {{sphere, 2.0}, {inner, 2.0}}};
  const BubbleEstimator e = makeBubbleEstimator(outer, 0.05);
  ASSERT_EQ(e.members.size(), 3u);
  EXPECT_DOUBLE_EQ(e.members[0].weight, 0.5);
  EXPECT_DOUBLE_EQ(e.members[1].weight, 0.125);
  EXPECT_DOUBLE_EQ(e.members[2].weight, 0.375);
  EXPECT_EQ(e.reach, 4);
}

TEST(AirField, CountsEqualTheNaiveLoopForEveryBubbleKind) {
  for (bool ground : {true, false}) {
    for (double fill : {0.3, 0.7}) {
      const VoxelRock rock = test::randomRock(23, 17, 19, ground ? 11 : 12, fill, ground);
      for (const auto& [name, bubble] : allBubbleKinds()) {
        const AirField field(rock, std::max(1, bubble.reach));
        const auto bound = field.bind(bubble);
        const GridLayout& g = rock.layout;
        for (int z = 0; z < g.nz; ++z)
          for (int y = 0; y < g.ny; ++y)
            for (int x = 0; x < g.nx; ++x)
              ASSERT_EQ(field.countAir(bound, x, y, z), naiveCountAir(rock, bubble, x, y, z))
                  << name << " at " << x << "," << y << "," << z << " ground=" << ground;
      }
    }
  }
}

// Runs of voxels along x, and every voxel alone, on one α path, against the
// naive loop: random grids, every bubble kind, rows shorter and longer than
// one load's piece (a long row is cut into pieces of AirField::kMaxPiece
// cells), piece counts that are and are not multiples of 8, ground on/off.
void expectRunsEqualTheNaiveLoop(AlphaPath path) {
  std::vector<NamedBubble> bubbles = allBubbleKinds();
  bubbles.push_back({"long ellipsoid (rows up to 61)", makeEllipsoidBubble({30.5, 2.0, 1.5})});
  bubbles.push_back({"long box (rows of 111)", makeBoxBubble({55.0, 1.0, 1.0})});
  bubbles.push_back({"sphere r19", makeSphereBubble(19.0)});
  for (bool ground : {true, false}) {
    const VoxelRock rock = test::randomRock(75, 9, 8, ground ? 21 : 22, 0.5, ground);
    const GridLayout& g = rock.layout;
    for (const auto& [name, bubble] : bubbles) {
      const AirField field(rock, std::max(1, bubble.reach));
      const auto bound = field.bind(bubble);
      std::uint64_t draw = 0;
      for (int z = 0; z < g.nz; ++z)
        for (int y = 0; y < g.ny; ++y)
          for (int x0 = 0; x0 < g.nx; ++x0) {
            // A run from x0 of 1..8 voxels at random offsets within 8 cells.
            std::uint8_t dx[AirField::kRunWidth] = {0};
            int n = 1;
            for (int d = 1; d < AirField::kRunWidth && x0 + d < g.nx; ++d)
              if (counterHash(7, purposeId("test-run"), draw++, 0) % 2) dx[n++] = std::uint8_t(d);
            int counts[AirField::kRunWidth];
            field.countAirRun(path, bound, x0, y, z, dx, n, counts);
            for (int k = 0; k < n; ++k)
              ASSERT_EQ(counts[k], naiveCountAir(rock, bubble, x0 + dx[k], y, z))
                  << alphaPathName(path) << ", " << name << " at " << x0 + dx[k] << "," << y << "," << z << " (run of "
                  << n << " from " << x0 << ") ground=" << ground;
            // The voxel alone (on the AVX-512 path: its pieces gathered eight at a time).
            const std::uint8_t alone[1] = {0};
            field.countAirRun(path, bound, x0, y, z, alone, 1, counts);
            ASSERT_EQ(counts[0], naiveCountAir(rock, bubble, x0, y, z))
                << alphaPathName(path) << ", " << name << " at " << x0 << "," << y << "," << z
                << " alone, ground=" << ground;
          }
    }
  }
}

TEST(AirField, PortableRunsEqualTheNaiveLoop) {
  expectRunsEqualTheNaiveLoop(AlphaPath::Portable);
}

TEST(AirField, Avx512RunsEqualTheNaiveLoop) {
  if (!alphaPathAvailable(AlphaPath::Avx512)) GTEST_SKIP() << "this CPU lacks AVX-512F/VPOPCNTDQ";
  expectRunsEqualTheNaiveLoop(AlphaPath::Avx512);
}

TEST(AirField, LongRowsAreCutIntoPiecesOfOneLoad) {
  const VoxelRock rock = test::randomRock(130, 5, 5, 3, 0.5, true);
  const AirField field(rock, 60);
  // A 121-cell row (box half extent 60): three pieces of at most 50 cells.
  EXPECT_EQ(field.bind(makeBoxBubble({60.0, 0.0, 0.0})).pieces, 3u);
  EXPECT_EQ(field.bind(makeSphereBubble(6.0)).pieces, makeSphereBubble(6.0).rows.size());
}

TEST(AirField, AnUnavailablePathCannotBeForced) {
  const AlphaPath before = alphaPath();
  EXPECT_NO_THROW(setAlphaPath(AlphaPath::Portable));
  EXPECT_EQ(alphaPath(), AlphaPath::Portable);
  if (alphaPathAvailable(AlphaPath::Avx512))
    EXPECT_NO_THROW(setAlphaPath(AlphaPath::Avx512));
  else
    EXPECT_THROW(setAlphaPath(AlphaPath::Avx512), std::invalid_argument);
  setAlphaPath(before);
}

TEST(RowSpans, ReadAndWriteLikeADenseArray) {
  GridLayout g;
  g.nx = 17, g.ny = 5, g.nz = 4;
  for (float fill : {0.f, 1.f}) {
    RowSpans spans(g, fill);
    std::vector<float> dense(g.cellCount(), fill);
    for (std::uint64_t i = 0; i < 3000; ++i) {
      const std::size_t cell = std::size_t(counterHash(5, purposeId("test-spans"), i, 0) % g.cellCount());
      // Half the writes put back the fill value, which must read back too.
      const float value = counterHash(5, purposeId("test-spans"), i, 1) % 2 ? fill : float(i % 7) * 0.5f;
      spans.set(cell, value);
      dense[cell] = value;
      ASSERT_EQ(spans[cell], value);
    }
    EXPECT_TRUE(spans.toDense() == dense);
    for (std::size_t cell = 0; cell < g.cellCount(); ++cell) ASSERT_EQ(spans[cell], dense[cell]);
    EXPECT_LE(spans.storedCells(), g.cellCount());
  }
}

TEST(AirField, CountsStayExactAfterCellsChange) {
  VoxelRock rock = test::randomRock(30, 12, 14, 5, 0.5, true);
  const Bubble bubble = makeSphereBubble(4.5);
  AirField field(rock, bubble.reach);
  const auto bound = field.bind(bubble);
  std::mt19937 rng(3);
  for (int step = 0; step < 400; ++step) {
    const int x = int(rng() % 30), y = int(rng() % 12), z = int(rng() % 14);
    const bool air = rng() % 2;
    rock.material[rock.layout.index(x, y, z)] = air ? Material::Air : Material::Rock;
    field.setAir(x, y, z, air);
  }
  for (int z = 0; z < 14; ++z)
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 30; ++x) ASSERT_EQ(field.countAir(bound, x, y, z), naiveCountAir(rock, bubble, x, y, z));
}

TEST(Exposure, IsOneHalfOnFlatFacesOfSphereAndCubeBubbles) {
  // A large block: the centre of each face is flat for any bubble that fits.
  const VoxelRock rock = blockRock(40, 8, 32);
  for (const Bubble& bubble : {makeSphereBubble(6.0), makeBoxBubble({4, 4, 4})}) {
    const AirField field(rock, bubble.reach);
    const auto bound = field.bind(bubble);
    const int faces[6][3] = {{31, 20, 20}, {8, 20, 20}, {20, 31, 20}, {20, 8, 20}, {20, 20, 31}, {20, 20, 8}};
    for (const auto& f : faces) {
      const double alpha = double(field.countAir(bound, f[0], f[1], f[2])) / bound.size;
      EXPECT_NEAR(calibratedExposure(alpha, bound.alpha_flat), 0.5, 1e-12);
    }
  }
}

TEST(Exposure, AveragesOneHalfOverTheSixFacesForAnyBubble) {
  const VoxelRock rock = blockRock(40, 8, 32);
  for (const auto& [name, bubble] : allBubbleKinds()) {
    const AirField field(rock, std::max(1, bubble.reach));
    const auto bound = field.bind(bubble);
    const int faces[6][3] = {{31, 20, 20}, {8, 20, 20}, {20, 31, 20}, {20, 8, 20}, {20, 20, 31}, {20, 20, 8}};
    double alpha_sum = 0.0, s_sum = 0.0;
    for (const auto& f : faces) {
      const double alpha = double(field.countAir(bound, f[0], f[1], f[2])) / bound.size;
      alpha_sum += alpha;
      s_sum += calibratedExposure(alpha, bound.alpha_flat);
    }
    // α averages to α_flat exactly; s is ½ up to the kink of the calibration.
    EXPECT_NEAR(alpha_sum / 6.0, bubble.alpha_flat, 1e-12) << name;
    EXPECT_NEAR(s_sum / 6.0, 0.5, 0.02) << name;
  }
}

TEST(Exposure, RisesOnEdgesAndHigherStillOnCorners) {
  const VoxelRock rock = blockRock(40, 8, 32);
  for (const Bubble& bubble : {makeSphereBubble(6.0), makeSphereBubble(3.0), makeBoxBubble({3, 3, 3})}) {
    const AirField field(rock, bubble.reach);
    const auto bound = field.bind(bubble);
    const auto s = [&](int x, int y, int z) {
      return calibratedExposure(double(field.countAir(bound, x, y, z)) / bound.size, bound.alpha_flat);
    };
    const double face = s(31, 20, 20), edge = s(31, 31, 20), corner = s(31, 31, 31);
    EXPECT_NEAR(face, 0.5, 1e-12);
    EXPECT_GT(edge, face + 0.1);
    EXPECT_GT(corner, edge + 0.05);
    EXPECT_LE(corner, 1.0);
    // Concave: the inside of an L (a voxel in a re-entrant edge) is below ½.
  }
}

TEST(Exposure, FallsBelowOneHalfInAReEntrantEdge) {
  VoxelRock rock = blockRock(40, 8, 32);
  // Carve a quarter out of the block: the voxel at the carved edge sees a concave edge.
  for (int z = 8; z < 32; ++z)
    for (int y = 20; y < 32; ++y)
      for (int x = 20; x < 32; ++x) rock.material[rock.layout.index(x, y, z)] = Material::Air;
  const Bubble bubble = makeSphereBubble(5.0);
  const AirField field(rock, bubble.reach);
  const auto bound = field.bind(bubble);
  // (19, 20, 20) lies on the face x = 19 where it meets the carved-out quarter.
  const double alpha = double(field.countAir(bound, 19, 20, 20)) / bound.size;
  EXPECT_LT(calibratedExposure(alpha, bound.alpha_flat), 0.4);
}

}  // namespace
}  // namespace rockbake
