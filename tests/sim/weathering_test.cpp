// The paper's results, reproduced (docs/model.md §11): cube → sphere, corner →
// cavern, profile follows durability, bubble shape, response curve, keyframes,
// resolution parity.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>

#include <tbb/global_control.h>

#include "sim/curvature.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

using test::cubePreset;

ResponseParams threshold(double t) {
  return {ResponseParams::Kind::Threshold, t, {}};
}
ResponseParams power(double p) {
  return {ResponseParams::Kind::Power, p, {}};
}

bool isRock(const VoxelRock& rock, int x, int y, int z) {
  return rock.layout.contains(x, y, z) && rock.material[rock.layout.index(x, y, z)] == Material::Rock;
}

TEST(Weathering, CubeBecomesASphere) {
  // Paper Fig. 9; docs/model.md §5's naive check: 48-voxel cube, radius-6 bubble.
  Preset p = cubePreset(4.8, 48, 0.6);
  p.response = threshold(0.5);
  p.stop.cycles = 1000;
  p.stop.rock_volume_fraction = 0.5;
  const VoxelRock cube = buildInitialRock(resolveShape(p), p);
  EXPECT_NEAR(test::surfaceDistanceSpread(cube), 0.127, 0.002);
  const WeatheringResult result = weatherRock(cube, p);
  const double remaining = double(result.rock.count(Material::Rock)) / double(cube.count(Material::Rock));
  EXPECT_LE(remaining, 0.5);
  EXPECT_GT(remaining, 0.45);
  EXPECT_LE(test::surfaceDistanceSpread(result.rock), 0.06);
}

TEST(Weathering, ThresholdLeavesFlatFacesAloneAndCyclesAreSynchronous) {
  Preset p = cubePreset(3.2, 32, 0.4);
  p.response = threshold(0.5);
  p.stop.cycles = 1;
  const VoxelRock cube = buildInitialRock(resolveShape(p), p);
  const WeatheringResult result = weatherRock(cube, p);
  // One cycle lowers the integrity of the voxels exposed at its start: the
  // centre of every face (s = ½, f = 0) keeps all of it, corners lose some.
  const GridLayout& g = cube.layout;
  const int lo = g.margin, hi = g.margin + 31, mid = g.margin + 16;
  const auto integrity = [&](int x, int y, int z) { return result.rock.integrity[g.index(x, y, z)]; };
  EXPECT_EQ(integrity(lo, mid, mid), 1.f);
  EXPECT_EQ(integrity(mid, hi, mid), 1.f);
  EXPECT_EQ(integrity(mid, mid, 31), 1.f);
  EXPECT_LT(integrity(lo, lo, 0), 0.8f);         // a corner: s well above ½
  EXPECT_EQ(integrity(lo + 1, lo + 1, 1), 1.f);  // behind it: not exposed at the start
  ASSERT_EQ(result.cycles.size(), 1u);
  EXPECT_EQ(result.cycles[0].rock + result.cycles[0].decimated, cube.count(Material::Rock));
}

// The chamfer (6-connected) depth of every initial rock voxel below the initial surface.
std::vector<int> depthBelowSurface(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::vector<int> depth(g.cellCount(), -1);
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < depth.size(); ++i)
    if (rock.material[i] != Material::Rock) depth[i] = 0, queue.push_back(i);
  while (!queue.empty()) {
    const std::size_t i = queue.front();
    queue.pop_front();
    const int x = int(i % g.nx), y = int((i / g.nx) % g.ny), z = int(i / (std::size_t(g.nx) * g.ny));
    const int d[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    for (const auto& o : d) {
      if (!g.contains(x + o[0], y + o[1], z + o[2])) continue;
      const std::size_t j = g.index(x + o[0], y + o[1], z + o[2]);
      if (depth[j] < 0) depth[j] = depth[i] + 1, queue.push_back(j);
    }
  }
  return depth;
}

TEST(Weathering, InsideCornerBecomesACavern) {
  // Paper Fig. 10: cavernous weathering hollows the sheltered corner.
  Preset p = cubePreset(3.0, 48, 0.3);
  p.grid.ground = true;
  p.shape.kind = InsideCornerShape{{3.0, 3.0, 3.0}, 1.0};
  p.bubbles[0].spheroidal = 0.0;
  p.bubbles[0].cavernous = 1.0;
  p.response = threshold(0.5);
  p.stop.cycles.reset();
  p.stop.time = 1.0;
  const VoxelRock corner = buildInitialRock(resolveShape(p), p);
  const WeatheringResult result = weatherRock(corner, p);
  const GridLayout& g = corner.layout;
  const std::vector<int> depth = depthBelowSurface(corner);

  // The re-entrant corner is the vertical edge at (x0 + wall, y0 + wall).
  const double corner_x = 0.0 + 1.0, corner_y = 0.0 + 1.0;  // the L is centred in a 3 × 3 domain
  int corner_depth = 0, open_face_depth = 0;
  bool overhang = false;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const std::size_t i = g.index(x, y, z);
        if (corner.material[i] != Material::Rock || result.rock.material[i] == Material::Rock) continue;
        const Vec3d c = g.center(x, y, z);
        const double from_corner = std::hypot(c[0] - corner_x, c[1] - corner_y);
        if (from_corner < 0.6) corner_depth = std::max(corner_depth, depth[i]);
        // The open faces: the L's outer back faces (x = 0 or y = 0), away from edges and the ground.
        const bool mid_height = c[2] > 0.8 && c[2] < 2.2;
        const bool on_back_face =
            mid_height && ((c[0] < 0.5 && c[1] > 0.8 && c[1] < 2.2) || (c[1] < 0.5 && c[0] > 0.8 && c[0] < 2.2));
        if (on_back_face) open_face_depth = std::max(open_face_depth, depth[i]);
        // An overhang: a hollowed voxel with rock still standing somewhere above it.
        for (int up = z + 1; up < g.nz && !overhang; ++up) overhang = isRock(result.rock, x, y, up);
      }
  RecordProperty("corner_depth_voxels", corner_depth);
  RecordProperty("open_face_depth_voxels", open_face_depth);
  EXPECT_GE(corner_depth, 3);
  EXPECT_GE(corner_depth, 2 * std::max(open_face_depth, 1));
  EXPECT_TRUE(overhang);
}

Preset columnPreset(int resolution) {
  Preset p = cubePreset(4.0, resolution, 0.25);
  p.grid.size = {4.0, 4.0, 6.0};
  p.grid.ground = true;
  p.shape.kind = CylinderShape{1.6, 6.0};
  p.response = power(1.0);
  p.stop.cycles.reset();
  p.stop.time = 1.0;
  return p;
}

// Mean radius (world units) of the rock in each layer, from its area.
TEST(Weathering, ProfileFollowsTheDurabilityGraph) {
  // Paper Fig. 15: durable layers stand proud, soft layers are cut back.
  Preset p = columnPreset(48);
  p.durability.graph.points = {{0.0, 2.0}, {0.3, 0.5}, {0.55, 2.5}, {0.8, 0.7}, {1.0, 1.5}};
  const WeatheringResult result = weatherRock(buildInitialRock(resolveShape(p), p), p);
  const GridLayout& g = result.rock.layout;
  const std::vector<double> radii = test::layerRadii(result.rock);
  std::vector<double> r, d;
  for (int z = 0; z < g.nz; ++z) {
    const double a = g.altitude(z);
    if (a < 0.05 || a > 0.9) continue;  // the rounded top and the foot are shaped by more than D
    double graph = 0;
    const auto& pts = p.durability.graph.points;
    for (std::size_t i = 1; i < pts.size(); ++i)
      if (a <= pts[i][0]) {
        graph = pts[i - 1][1] + (a - pts[i - 1][0]) / (pts[i][0] - pts[i - 1][0]) * (pts[i][1] - pts[i - 1][1]);
        break;
      }
    r.push_back(radii[std::size_t(z)]);
    d.push_back(graph);
  }
  const double correlation = test::pearson(r, d);
  RecordProperty("pearson", std::to_string(correlation));
  EXPECT_GE(correlation, 0.9);
}

// Standard deviation of the rock voxels' coordinates along each axis (voxels).
std::array<double, 3> rockSpread(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::array<double, 3> sum{}, sum_sq{};
  double n = 0;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (isRock(rock, x, y, z)) {
          const double p[3] = {double(x), double(y), double(z)};
          for (int a = 0; a < 3; ++a) sum[a] += p[a], sum_sq[a] += p[a] * p[a];
          n += 1;
        }
  std::array<double, 3> spread;
  for (int a = 0; a < 3; ++a) spread[a] = std::sqrt(sum_sq[a] / n - (sum[a] / n) * (sum[a] / n));
  return spread;
}

TEST(Weathering, CubeTakesTheEllipsoidBubblesProportions) {
  // Paper Fig. 11: a bubble elongated along x. Under a bubble with the
  // proportions of an ellipsoid, that ellipsoid is the shape of uniform
  // exposure, so the cube keeps its length along x and is cut back along y
  // and z. (The bubble must span several voxels across its short axes: with
  // only ~3, the half-voxel offset of face voxels dominates and flat x faces
  // read as convex; see docs/model.md.)
  Preset p = cubePreset(4.0, 60, 0.3);
  p.bubbles[0].bubble = {BubbleSpec::Kind::Ellipsoid, {1.2, 0.4, 0.4}, {}};
  p.response = threshold(0.5);
  p.stop.cycles = 1000;
  p.stop.rock_volume_fraction = 0.4;
  const auto spread = rockSpread(weatherRock(buildInitialRock(resolveShape(p), p), p).rock);
  RecordProperty("spread_x", std::to_string(spread[0]));
  RecordProperty("spread_y", std::to_string(spread[1]));
  EXPECT_GT(spread[0], 1.08 * spread[1]);
  EXPECT_NEAR(spread[1], spread[2], 0.05);

  // The same cube under a sphere bubble stays isotropic.
  p.bubbles[0].bubble = {BubbleSpec::Kind::Sphere, {0.4, 0, 0}, {}};
  const auto round = rockSpread(weatherRock(buildInitialRock(resolveShape(p), p), p).rock);
  EXPECT_NEAR(round[0], round[1], 0.05);
  EXPECT_NEAR(round[0], round[2], 0.05);
}

// How far the corner retreated along the diagonal relative to the face centres.
double cornerToFaceRetreat(const ResponseParams& response) {
  Preset p = cubePreset(4.0, 40, 0.4);
  p.response = response;
  p.stop.cycles = 8;
  const VoxelRock cube = buildInitialRock(resolveShape(p), p);
  const WeatheringResult result = weatherRock(cube, p);
  const int m = cube.layout.margin, mid = m + 20;
  int face = 0;
  while (!isRock(result.rock, m + face, mid, mid)) ++face;
  int corner = 0;
  while (!isRock(result.rock, m + corner, m + corner, corner)) ++corner;
  const double corner_retreat = corner * std::sqrt(3.0);
  return corner_retreat / std::max(face, 1);
}

TEST(Weathering, ResponseCurveChangesHowCornersRetreatRelativeToFaces) {
  // Paper Fig. 13.
  const double linear = cornerToFaceRetreat(power(1.0));
  const double cubic = cornerToFaceRetreat(power(3.0));
  const double thresholded = cornerToFaceRetreat(threshold(0.5));
  RecordProperty("linear", std::to_string(linear));
  RecordProperty("cubic", std::to_string(cubic));
  RecordProperty("threshold", std::to_string(thresholded));
  EXPECT_GT(cubic, 1.5 * linear);
  EXPECT_GT(thresholded, 1.5 * linear);
}

TEST(Weathering, KeyframeThatSoftensABandSpeedsUpItsRetreatAfterItsTime) {
  Preset plain = columnPreset(40);
  plain.stop.time = 1.5;
  Preset edited = plain;
  DurabilityKeyframe keyframe;
  keyframe.at = 0.75;
  keyframe.graph = DurabilityGraph{{{0.0, 1.0}, {0.39, 1.0}, {0.4, 0.25}, {0.6, 0.25}, {0.61, 1.0}, {1.0, 1.0}}, {}};
  edited.durability.keyframes = {keyframe};

  const VoxelRock start = buildInitialRock(resolveShape(plain), plain);
  const WeatheringResult a = weatherRock(start, plain);
  const WeatheringResult b = weatherRock(start, edited);
  const GridLayout& g = start.layout;
  const int at_cycle = int(std::ceil(0.75 / g.h));
  for (int c = 0; c < at_cycle; ++c) EXPECT_EQ(a.cycles[std::size_t(c)].rock, b.cycles[std::size_t(c)].rock) << c;

  const std::vector<double> ra = test::layerRadii(a.rock), rb = test::layerRadii(b.rock);
  for (int z = 0; z < g.nz; ++z) {
    const double alt = g.altitude(z);
    if (alt > 0.45 && alt < 0.55) {
      EXPECT_LT(rb[std::size_t(z)], ra[std::size_t(z)] - 2 * g.h) << "z " << z;
    }
    if (alt > 0.1 && alt < 0.3) {
      EXPECT_NEAR(rb[std::size_t(z)], ra[std::size_t(z)], 1e-9) << "z " << z;
    }
  }
}

// Rock occupancy of `fine` (twice the resolution) resampled onto `coarse`'s
// voxels by majority of the 8 fine voxels whose centres fall in each.
double resampledIoU(const VoxelRock& coarse, const VoxelRock& fine) {
  const GridLayout& c = coarse.layout;
  const GridLayout& f = fine.layout;
  std::size_t both = 0, either = 0;
  for (int z = 0; z < c.nz; ++z)
    for (int y = 0; y < c.ny; ++y)
      for (int x = 0; x < c.nx; ++x) {
        const Vec3d p = c.center(x, y, z);
        int votes = 0;
        for (int dz = 0; dz < 2; ++dz)
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
              const int fx = int(std::floor((p[0] - f.origin[0]) / f.h - 1 + dx + 0.5));
              const int fy = int(std::floor((p[1] - f.origin[1]) / f.h - 1 + dy + 0.5));
              const int fz = int(std::floor((p[2] - f.origin[2]) / f.h - 1 + dz + 0.5));
              votes += isRock(fine, fx, fy, fz);
            }
        const bool a = isRock(coarse, x, y, z), b = votes >= 4;
        both += a && b;
        either += a || b;
      }
  return double(both) / double(either);
}

TEST(Weathering, SamePresetAtTwoResolutionsGivesTheSameRock) {
  // docs/model.md §9: everything in world units, one cycle = h units of time.
  Preset p = columnPreset(48);
  p.durability.graph.points = {{0.0, 1.5}, {0.5, 0.6}, {1.0, 1.2}};
  p.bubbles[0].cavernous = 0.3;
  p.stop.time = 1.2;
  Preset fine = p;
  fine.grid.resolution = 96;
  const WeatheringResult a = weatherRock(buildInitialRock(resolveShape(p), p), p);
  const WeatheringResult b = weatherRock(buildInitialRock(resolveShape(fine), fine), fine);
  const double iou = resampledIoU(a.rock, b.rock);
  RecordProperty("iou", std::to_string(iou));
  EXPECT_GE(iou, 0.85);
}

TEST(Weathering, UntilStopsAtTheRockVolumeFraction) {
  Preset p = cubePreset(3.2, 32, 0.4);
  p.stop.cycles = 500;
  p.stop.rock_volume_fraction = 0.8;
  const VoxelRock cube = buildInitialRock(resolveShape(p), p);
  const WeatheringResult result = weatherRock(cube, p);
  ASSERT_FALSE(result.cycles.empty());
  EXPECT_LT(result.cycles.size(), 500u);
  EXPECT_LE(double(result.cycles.back().rock), 0.8 * double(cube.count(Material::Rock)));
  ASSERT_GT(result.cycles.size(), 1u);
  EXPECT_GT(double(result.cycles[result.cycles.size() - 2].rock), 0.8 * double(cube.count(Material::Rock)));
}

TEST(Weathering, SameRockOnAnyThreadCountAndAlphaPath) {
  // Everything on: ground, rockfall, colluvium with removal, spheroidal and
  // cavernous weathering, and an ellipsoid whose rows (up to 55 cells) are
  // longer than one load's piece.
  Preset p = cubePreset(2.4, 40, 0.3);  // h = 0.06
  p.grid.ground = true;
  p.grid.size = {3.6, 3.6, 2.4};
  p.shape.center = Vec3d{1.8, 1.8, 0.0};
  p.bubbles[0].bubble.kind = BubbleSpec::Kind::Ellipsoid;
  p.bubbles[0].bubble.extents = {1.65, 0.3, 0.24};
  p.bubbles[0].spheroidal = 0.7;
  p.bubbles[0].cavernous = 0.3;
  p.response = power(1.0);
  p.rockfall.mode = RockfallMode::Drop;
  p.colluvium = {0.5, 35.0, 0.05};
  p.stop.cycles = 8;
  const VoxelRock start = buildInitialRock(resolveShape(p), p);

  struct Run {
    const char* name;
    int threads;
    AlphaPath path;
  };
  std::vector<Run> runs = {{"1 thread, portable", 1, AlphaPath::Portable},
                           {"2 threads, portable", 2, AlphaPath::Portable}};
  if (alphaPathAvailable(AlphaPath::Avx512))
    runs.insert(runs.end(), {{"1 thread, avx512", 1, AlphaPath::Avx512}, {"2 threads, avx512", 2, AlphaPath::Avx512}});
  const AlphaPath before = alphaPath();
  std::vector<WeatheringResult> results;
  for (const Run& run : runs) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(run.threads));
    setAlphaPath(run.path);
    WeatheringSimulation sim(start, p);
    WeatheringResult result;
    while (!sim.finished()) {
      result.cycles.push_back(sim.step());
      // The colluvium count kept from deposits, crumbles and removals is the real one.
      ASSERT_EQ(result.cycles.back().colluvium, sim.rock().count(Material::Colluvium)) << run.name;
    }
    result.rock = sim.release();
    results.push_back(std::move(result));
  }
  setAlphaPath(before);
  const WeatheringResult& first = results.front();
  std::size_t decimated = 0, deposited = 0;
  for (const auto& c : first.cycles) decimated += c.decimated, deposited += c.deposited;
  EXPECT_GT(decimated, 1000u);
  EXPECT_GT(deposited, 100u);
  for (std::size_t r = 1; r < runs.size(); ++r) {
    const WeatheringResult& other = results[r];
    EXPECT_TRUE(other.rock.material == first.rock.material) << runs[r].name;
    EXPECT_TRUE(other.rock.integrity.toDense() == first.rock.integrity.toDense()) << runs[r].name;
    EXPECT_TRUE(other.rock.durability.toDense() == first.rock.durability.toDense()) << runs[r].name;
    ASSERT_EQ(other.cycles.size(), first.cycles.size());
    for (std::size_t i = 0; i < first.cycles.size(); ++i) {
      EXPECT_EQ(other.cycles[i].exposed, first.cycles[i].exposed) << runs[r].name;
      EXPECT_EQ(other.cycles[i].fallen, first.cycles[i].fallen) << runs[r].name;
      EXPECT_EQ(other.cycles[i].removed, first.cycles[i].removed) << runs[r].name;
    }
  }
}

TEST(Weathering, TimeBecomesCyclesByVoxelSize) {
  Preset p = cubePreset(3.0, 30, 0.3);  // h = 0.1
  p.stop.cycles.reset();
  p.stop.time = 3.0;
  EXPECT_EQ(plannedCycles(p, 0.1), 30);
  p.stop.time = 3.01;
  EXPECT_EQ(plannedCycles(p, 0.1), 31);
  p.stop.time.reset();
  p.stop.cycles = 7;
  EXPECT_EQ(plannedCycles(p, 0.1), 7);
}

}  // namespace
}  // namespace rockbake
