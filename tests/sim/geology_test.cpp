// Geology beyond the altitude graph (docs/model.md §4, §8): shape variation per
// seed, dipping strata, joints, a case-hardened rind, and their validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "inputs/resolve_shape.h"
#include "preset/library.h"
#include "preset/load_preset.h"
#include "sim/durability.h"
#include "sim/rock_measures.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

bool isRock(const VoxelRock& rock, int x, int y, int z) {
  return rock.layout.contains(x, y, z) && rock.material[rock.layout.index(x, y, z)] == Material::Rock;
}

VoxelRock initialRock(const Preset& p) {
  return buildInitialRock(resolveShape(p), p);
}
VoxelRock weathered(const Preset& p) {
  return weatherRock(initialRock(p), p).rock;
}

// Whether each stays its kind at every seed is tests/sim/family_test.cpp's
// (docs/model.md §12): sizes and proportions now differ by design.
TEST(Geology, EverySeedOfTheCatalogueIsADifferentRock) {
  const fs::path file = test::sourceDir() / "presets" / "library.yaml";
  const Library library = loadLibrary(file);
  ASSERT_GE(library.entries.size(), 10u);
  for (const LibraryEntry& entry : library.entries) {
    ASSERT_GE(entry.seeds.size(), 2u) << entry.name;
    std::vector<VoxelRock> rocks;
    for (std::size_t s = 0; s < 2; ++s)
      rocks.push_back(weathered(loadPreset(entry.preset_file, {{}, entry.seeds[s], 48})));
    const double iou = alignedIoU(rocks[0], rocks[1]);
    RecordProperty(entry.name + "_aligned_iou", std::to_string(iou));
    EXPECT_LE(iou, 0.7) << entry.name << ": seeds " << entry.seeds[0] << " and " << entry.seeds[1];
    // Same seed, same rock: the initial rock (shape and durability) is rebuilt identically.
    const Preset again = loadPreset(entry.preset_file, {{}, entry.seeds[0], 48});
    const VoxelRock first = initialRock(again), second = initialRock(again);
    EXPECT_TRUE(first.material == second.material && first.durability.toDense() == second.durability.toDense())
        << entry.name;
  }
}

// A box on the ground in a domain `domain`, one sphere bubble, no debris.
Preset boxPreset(const Vec3d& domain, const Vec3d& box, int resolution, double bubble, double spheroidal,
                 double cavernous) {
  Preset p;
  p.name = "geology";
  p.seed = 5;
  p.grid.size = domain;
  p.grid.resolution = resolution;
  p.shape.kind = BoxShape{box};
  BubbleBand band;
  band.bubble.kind = BubbleSpec::Kind::Sphere;
  band.bubble.extents = {bubble, 0, 0};
  band.spheroidal = spheroidal;
  band.cavernous = cavernous;
  p.bubbles = {band};
  p.colluvium.yield = 0.0;
  return p;
}

TEST(Geology, ASoftBedDipping30DegreesIsCutBackAlongATiltedNotch) {
  // A slab long in x, thin in y; one soft bed through the domain's centre,
  // striking along +y, so it dips 30° towards +x on the slab's long faces.
  Preset p = boxPreset({4.0, 1.6, 3.2}, {4.0, 1.0, 3.2}, 48, 0.25, 1.0, 0.3);
  p.rockfall.mode = RockfallMode::Off;
  p.durability.graph.points = {{0.0, 3.0}, {0.44, 3.0}, {0.5, 0.3}, {0.56, 3.0}, {1.0, 3.0}};
  p.durability.strata = StrataParams{30.0, 0.0, 0.0, 1.0};
  p.stop.time = 0.15;
  const VoxelRock rock = weathered(p);
  const GridLayout& g = rock.layout;
  // For every x away from the slab's ends: the height where the slab is thinnest (the notch's floor).
  std::vector<double> xs, zs;
  for (int x = 0; x < g.nx; ++x) {
    const double wx = g.center(x, 0, 0)[0];
    if (wx < 0.5 || wx > 3.5) continue;
    int best_z = -1, best = 1 << 30;
    for (int z = 2; z < g.nz; ++z) {
      const double wz = g.center(0, 0, z)[2];
      if (wz > 3.0) break;
      int thickness = 0;
      for (int y = 0; y < g.ny; ++y) thickness += isRock(rock, x, y, z);
      if (thickness < best) best = thickness, best_z = z;
    }
    xs.push_back(wx);
    zs.push_back(g.center(0, 0, best_z)[2]);
  }
  ASSERT_GT(xs.size(), 10u);
  // Least squares z = a + b x.
  const double n = double(xs.size());
  const double mx = std::accumulate(xs.begin(), xs.end(), 0.0) / n, mz = std::accumulate(zs.begin(), zs.end(), 0.0) / n;
  double sxz = 0, sxx = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) sxz += (xs[i] - mx) * (zs[i] - mz), sxx += (xs[i] - mx) * (xs[i] - mx);
  const double slope = sxz / sxx;
  const double dip = std::atan(-slope) * 180.0 / M_PI;  // descending towards +x, the strike's right
  RecordProperty("dip", std::to_string(dip));
  EXPECT_NEAR(dip, 30.0, 8.0);
}

TEST(Geology, AJointedBlockSplitsAlongItsJointsIntoPillars) {
  // A block 3.6 long in x, one set of vertical joints striking along +y
  // (planes x = const) 1.2 apart, 0.1 wide, 8× weaker.
  Preset p = boxPreset({4.0, 1.6, 1.6}, {3.6, 1.0, 1.4}, 48, 0.2, 1.0, 0.5);
  p.rockfall.mode = RockfallMode::Off;
  p.durability.graph.points = {{0.0, 2.0}, {1.0, 2.0}};
  const JointSet joints{0.0, 90.0, 1.2, 0.2, 0.1, 0.1};
  p.durability.joints = {joints};
  const Geology geology(p.durability, p.grid.size, p.seed);
  const VoxelRock initial = initialRock(p);
  const GridLayout& g = initial.layout;

  // Weathered a little: the removed rock lies along the planes.
  p.stop.time = 0.15;
  const VoxelRock early = weathered(p);
  std::size_t removed = 0, removed_near = 0, rock = 0, rock_near = 0;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        if (!isRock(initial, x, y, z)) continue;
        const bool near = std::abs(geology.jointDistance(0, g.center(x, y, z))) <= joints.width + g.h / 2;
        rock += 1, rock_near += near;
        if (!isRock(early, x, y, z)) removed += 1, removed_near += near;
      }
  ASSERT_GT(removed, 0u);
  const double zone_share = double(rock_near) / double(rock), removed_share = double(removed_near) / double(removed);
  RecordProperty("zone_share", std::to_string(zone_share));
  RecordProperty("removed_share", std::to_string(removed_share));
  EXPECT_GE(removed_share, 3.0 * zone_share) << "removed rock should concentrate at the joints";
  EXPECT_GE(removed_share, 0.5);

  // Weathered long enough: separate pillars, one between each pair of planes crossing the block.
  int planes = 0;
  for (int x = 0; x < g.nx; ++x) {
    const Vec3d c = g.center(x, g.ny / 2, g.nz / 2), next = g.center(x + 1, g.ny / 2, g.nz / 2);
    const bool inside = c[0] > 0.2 + 0.3 && next[0] < 3.8 - 0.3;  // the block spans 0.2..3.8
    if (inside && (geology.jointDistance(0, c) < 0) != (geology.jointDistance(0, next) < 0) &&
        std::abs(geology.jointDistance(0, c)) < g.h)
      ++planes;
  }
  ASSERT_GE(planes, 2);
  p.stop.time = 0.6;
  const VoxelRock late = weathered(p);
  EXPECT_EQ(test::voxelComponents(initial), 1u);
  EXPECT_GE(test::voxelComponents(late), std::size_t(planes + 1));
}

TEST(Geology, BehindABreachedRindTheRockHollowsUnderALip) {
  // A box whose 0.15-deep rind is 4× as durable as the rock inside, under
  // cavernous weathering that leaves flat faces alone (threshold ½). A breach:
  // a small hole through the rind in the middle of the +y face.
  Preset p = boxPreset({3.0, 3.0, 3.0}, {2.4, 2.4, 2.4}, 48, 0.3, 0.0, 1.0);
  p.response = {ResponseParams::Kind::Threshold, 0.5, {}};
  p.rockfall.mode = RockfallMode::Off;
  p.durability.rind = RindParams{0.15, 4.0};
  p.stop.time = 1.5;
  VoxelRock rock = initialRock(p);
  const GridLayout& g = rock.layout;
  // The +y face: the last rock layer in y at the box's centre.
  const int cx = g.nx / 2, cz = int(1.2 / g.h);
  int face = 0;
  for (int y = 0; y < g.ny; ++y)
    if (isRock(rock, cx, y, cz)) face = y;
  const int rind_voxels = int(std::ceil(0.15 / g.h));
  for (int dz = -1; dz <= 1; ++dz)
    for (int dx = -1; dx <= 1; ++dx)
      for (int y = face - rind_voxels; y <= face; ++y) rock.material[g.index(cx + dx, y, cz + dz)] = Material::Air;
  const VoxelRock after = weatherRock(rock, p).rock;

  // Depth of the hollow: how far behind the face the rock retreated at the breach.
  int hollow = 0;
  for (int y = face; y >= 0 && !isRock(after, cx, y, cz); --y) hollow = face - y + 1;
  // The rind's own retreat: the face's retreat far from the breach.
  int rind_retreat = 0;
  for (int y = face; y >= 0 && !isRock(after, cx - int(0.7 / g.h), y, cz); --y) rind_retreat = face - y + 1;
  RecordProperty("hollow_voxels", hollow);
  RecordProperty("rind_retreat_voxels", rind_retreat);
  EXPECT_GT(hollow, rind_voxels + 2) << "the hollow should reach well behind the rind";
  EXPECT_GT(hollow, 2 * std::max(rind_retreat, 1));

  // The lip: the hollow is taller behind the rind than its mouth in the face,
  // so rind rock overhangs it.
  const auto openHeight = [&](int y) {
    int lo = cz, hi = cz;
    while (hi + 1 < g.nz && !isRock(after, cx, y, hi + 1)) ++hi;
    while (lo - 1 >= 0 && !isRock(after, cx, y, lo - 1)) --lo;
    return hi - lo + 1;
  };
  const int mouth = openHeight(face);
  int chamber = 0;
  for (int y = face - rind_voxels - 1; y > face - hollow; --y) chamber = std::max(chamber, openHeight(y));
  RecordProperty("mouth_voxels", mouth);
  RecordProperty("chamber_voxels", chamber);
  EXPECT_GT(chamber, mouth + 1) << "rind rock should overhang the hollow";
  EXPECT_TRUE(isRock(after, cx, face, cz + (chamber + 1) / 2)) << "the lip above the mouth stands";
}

std::string errorOf(const std::string& appended) {
  try {
    parsePreset(std::string(test::kSmallPreset) + appended, "dir/p.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Geology, ReadsTheGeologyKeys) {
  const Preset p = parsePreset(
      std::string(test::kSmallPreset) + R"(durability:
  strata: {dip: 12, strike: 40, warp: {amplitude: 0.1, period: 3.0}}
  joints:
    - {strike: 30, dip: 85, spacing: 0.9, jitter: 0.25, width: 0.05, factor: 0.3}
  rind: {depth: 0.08, factor: 2.5}
)",
      "dir/p.yaml", {{"shape.variation={amplitude: 0.15, period: 1.2, octaves: 3}"}, std::nullopt, std::nullopt});
  ASSERT_TRUE(p.shape.variation.has_value());
  EXPECT_EQ(p.shape.variation->period, 1.2);
  EXPECT_EQ(p.shape.variation->octaves, 3);
  ASSERT_TRUE(p.durability.strata.has_value());
  EXPECT_EQ(p.durability.strata->dip, 12.0);
  EXPECT_EQ(p.durability.strata->warp_period, 3.0);
  ASSERT_EQ(p.durability.joints.size(), 1u);
  EXPECT_EQ(p.durability.joints[0].jitter, 0.25);
  EXPECT_EQ(p.durability.joints[0].factor, 0.3);
  ASSERT_TRUE(p.durability.rind.has_value());
  EXPECT_EQ(p.durability.rind->depth, 0.08);
  // Without them, the paper's graph: nothing set.
  const Preset plain = parsePreset(test::kSmallPreset, "dir/p.yaml");
  EXPECT_FALSE(plain.shape.variation || plain.durability.strata || plain.durability.rind);
  EXPECT_TRUE(plain.durability.joints.empty());
}

TEST(Geology, BadValuesNameTheirFileLineColumnAndKeyPath) {
  // kSmallPreset is twelve lines: what is appended starts on line 13.
  const std::string joint = "durability:\n  joints:\n    - {strike: 0, dip: 90, ";
  EXPECT_EQ(errorOf(joint + "spacing: -1, width: 0.1, factor: 0.5}\n"),
            "dir/p.yaml:15:37: durability.joints.0.spacing: must be greater than 0, found -1");
  EXPECT_EQ(errorOf("durability:\n  joints:\n    - {strike: 0, dip: 95, spacing: 1, width: 0.1, factor: 0.5}\n"),
            "dir/p.yaml:15:24: durability.joints.0.dip: must be in [0, 90], found 95");
  EXPECT_EQ(errorOf(joint + "spacing: 1, width: 1.5, factor: 0.5}\n"),
            "dir/p.yaml:15:47: durability.joints.0.width: must be less than spacing (1), found 1.5 (a joint zone "
            "as wide as the spacing leaves no sound rock between the planes)");
  EXPECT_EQ(errorOf(joint + "spacing: 1, width: 0.1, factor: 0}\n"),
            "dir/p.yaml:15:60: durability.joints.0.factor: must be greater than 0, found 0");
  EXPECT_EQ(errorOf("durability:\n  strata: {dip: -5}\n"),
            "dir/p.yaml:14:17: durability.strata.dip: must be in [0, 90], found -5");
  EXPECT_EQ(errorOf("durability:\n  rind: {depth: 0.1, factor: -2}\n"),
            "dir/p.yaml:14:30: durability.rind.factor: must be greater than 0, found -2");
  EXPECT_EQ(errorOf("durability:\n  joints:\n    - {spacing: 1, factor: 0.5}\n"),
            "dir/p.yaml:15:7: durability.joints.0: a joint set needs 'width' (world units either side of a plane)");
}

}  // namespace
}  // namespace rockbake
