// The surface look (mesh/surface_look.h): stain streaks where water runs, drips from overhangs,
// the damp foot, dust on ledges, scars, determinism and the "look: none" path. The shapes are
// profiles in the x–z plane swept along y, meshed by hand, with a voxel grid of the same solid.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include <tbb/global_control.h>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"
#include "mesh/surface_look.h"

namespace rockbake {
namespace {

using Point2 = std::array<double, 2>;  // (x, z)
// The corners of a profile at y, in the same number for every y, walked so that the solid is
// on the right (up the left face, along the top in +x, down the right face): the swept faces
// then face outwards.
using Profile = std::function<std::vector<Point2>(double y)>;

constexpr double kWidth = 8.0;  // the sweep along y, world units
constexpr double kH = 0.5;      // voxel size

void computeNormals(SurfaceMesh& m) {
  m.normals.assign(m.positions.size(), {0, 0, 0});
  std::vector<std::array<double, 3>> sum(m.positions.size(), {0, 0, 0});
  for (const auto& t : m.triangles) {
    const auto &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (std::uint32_t i : t)
      for (int k = 0; k < 3; ++k) sum[i][k] += n[k];
  }
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double len = std::sqrt(sum[i][0] * sum[i][0] + sum[i][1] * sum[i][1] + sum[i][2] * sum[i][2]);
    for (int k = 0; k < 3; ++k) m.normals[i][k] = float(sum[i][k] / len);
  }
}

// The profile swept from y = 0 to kWidth, vertices about `spacing` apart, with the baked
// attributes of bare rock: never covered, flat curvature, exposure age 1 (the initial surface).
SurfaceMesh sweep(const Profile& profile, double spacing) {
  const std::vector<Point2> mid = profile(0.5 * kWidth);
  std::vector<int> steps;
  for (std::size_t s = 0; s + 1 < mid.size(); ++s)
    steps.push_back(
        std::max(1, int(std::ceil(std::hypot(mid[s + 1][0] - mid[s][0], mid[s + 1][1] - mid[s][1]) / spacing))));
  int ni = 1;
  for (int k : steps) ni += k;
  const int nj = int(std::ceil(kWidth / spacing)) + 1;
  SurfaceMesh m;
  m.name = "rock";
  for (int j = 0; j < nj; ++j) {
    const double y = kWidth * j / (nj - 1);
    const std::vector<Point2> c = profile(y);
    for (std::size_t s = 0; s + 1 < c.size(); ++s)
      for (int k = 0; k < steps[s] + (s + 2 == c.size() ? 1 : 0); ++k) {
        const double t = double(k) / steps[s];
        m.positions.push_back(
            {float(c[s][0] + t * (c[s + 1][0] - c[s][0])), float(y), float(c[s][1] + t * (c[s + 1][1] - c[s][1]))});
      }
  }
  const auto at = [&](int i, int j) { return std::uint32_t(i + ni * j); };
  for (int j = 0; j + 1 < nj; ++j)
    for (int i = 0; i + 1 < ni; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
      m.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  computeNormals(m);
  const std::size_t n = m.positions.size();
  m.colluvium.assign(n, 0.0f);
  m.curvature.assign(n, 0.5f);
  m.altitude.assign(n, 0.0f);
  m.history.assign(n, {1.0f, 0.0f, 0.0f});
  return m;
}

bool inside(const std::vector<Point2>& corners, double x, double z) {
  // The profile closed along the ground (its last corner back to its first).
  bool in = false;
  for (std::size_t a = 0, b = corners.size() - 1; a < corners.size(); b = a++) {
    const Point2 &p = corners[a], &q = corners[b];
    if ((p[1] > z) != (q[1] > z) && x < p[0] + (z - p[1]) * (q[0] - p[0]) / (q[1] - p[1])) in = !in;
  }
  return in;
}

// A grid over x −1…9, y −1…kWidth+1, z 0…9 holding the swept solid as rock.
VoxelRock voxelize(const Profile& profile, bool ground = true) {
  VoxelRock rock;
  GridLayout& g = rock.layout;
  g.h = kH;
  g.origin = {-1.0, -1.0, 0.0};
  g.nx = int(10.0 / kH);
  g.ny = int((kWidth + 2.0) / kH);
  g.nz = int(9.0 / kH);
  g.domain_height = 9.0;
  g.ground = ground;
  rock.material.assign(g.cellCount(), Material::Air);
  for (int y = 0; y < g.ny; ++y) {
    const double cy = g.center(0, y, 0)[1];
    if (cy < 0 || cy > kWidth) continue;
    const std::vector<Point2> c = profile(cy);
    for (int z = 0; z < g.nz; ++z)
      for (int x = 0; x < g.nx; ++x) {
        const Vec3d p = g.center(x, y, z);
        if (inside(c, p[0], p[2])) rock.material[g.index(x, y, z)] = Material::Rock;
      }
  }
  return rock;
}

std::size_t nearest(const SurfaceMesh& m, double x, double y, double z) {
  std::size_t best = 0;
  double best_d = std::numeric_limits<double>::max();
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const auto& p = m.positions[v];
    const double d = (p[0] - x) * (p[0] - x) + (p[1] - y) * (p[1] - y) + (p[2] - z) * (p[2] - z);
    if (d < best_d) best_d = d, best = v;
  }
  return best;
}

float lookAt(const SurfaceMesh& m, int channel, double x, double y, double z) {
  return m.look[nearest(m, x, y, z)][channel];
}

enum Channel { kAge = 0, kStain = 1, kMoisture = 2, kDust = 3 };

// Only the stain in G: no varnish.
SurfaceLookParams stainOnly(const VoxelRock& rock) {
  SurfaceLookParams p;
  p.varnish = 0.0;
  p.rock = &rock;
  return p;
}

// A block whose top tilts gently towards a gutter along y = kWidth / 2 and towards its lip at
// x = 5, over a vertical face down to the ground.
std::vector<Point2> gutterBlock(double y) {
  const auto top = [&](double x) { return 6.0 + 0.1 * (5.0 - x) + 0.3 * std::abs(y - 0.5 * kWidth); };
  return {{0, 0}, {0, top(0)}, {5, top(5)}, {5, 0}};
}

TEST(Flow, StainsBelowALipInAStreak) {
  AssetMeshes meshes;
  meshes.rock = sweep(gutterBlock, 0.125);
  const VoxelRock rock = voxelize(gutterBlock);
  makeSurfaceLook(meshes, stainOnly(rock));
  const SurfaceMesh& m = meshes.rock;
  ASSERT_EQ(m.look.size(), m.positions.size());
  const double mid = 0.5 * kWidth;
  // The face below where the gutter pours over the lip, and beside it, 5 voxels either way.
  const float below = lookAt(m, kStain, 5.0, mid, 3.0);
  const float beside = std::max(lookAt(m, kStain, 5.0, mid - 2.5, 3.0), lookAt(m, kStain, 5.0, mid + 2.5, 3.0));
  EXPECT_GT(below, 0.4f);
  EXPECT_GT(below, 2.0f * beside) << "below " << below << ", beside " << beside;
  // The streak runs the height of the face.
  EXPECT_GT(lookAt(m, kStain, 5.0, mid, 1.0), 0.4f);
  EXPECT_GT(lookAt(m, kStain, 5.0, mid, 5.5), 0.4f);
  // The gently tilted top, its gutter included, stays far cleaner than the face below.
  EXPECT_LT(lookAt(m, kStain, 4.0, mid, 6.1), 0.25f * below);
  EXPECT_LT(lookAt(m, kStain, 2.5, mid - 1.5, 6.7), 0.1f);
}

// The same block with its top pitted (hollows a few hundredths deep, a voxel apart, deeper than
// its slope): the pits fill and spill, and their water still pours over the lip (kept in the
// pits, far less would: a stain of about 0.15).
TEST(Flow, HollowsFillAndSpill) {
  AssetMeshes meshes;
  meshes.rock = sweep(gutterBlock, 0.125);
  SurfaceMesh& m = meshes.rock;
  for (auto& p : m.positions)
    if (p[2] > 5.99f && p[0] > 0.01f && p[0] < 4.99f)
      p[2] += float(0.05 * std::sin(2 * M_PI * p[0] / kH) * std::sin(2 * M_PI * p[1] / kH));
  computeNormals(m);
  const VoxelRock rock = voxelize(gutterBlock);
  makeSurfaceLook(meshes, stainOnly(rock));
  const double mid = 0.5 * kWidth;
  EXPECT_GT(lookAt(m, kStain, 5.0, mid, 3.0), 0.6f);
}

// A box with a flat top, bumped by a few hundredths so that the rain gathers in its hollows.
std::vector<Point2> flatBox(double y) {
  (void)y;
  return {{0, 0}, {0, 4}, {5, 4}, {5, 0}};
}

TEST(Flow, AFlatOpenTopStaysUnstained) {
  AssetMeshes meshes;
  meshes.rock = sweep(flatBox, 0.125);
  SurfaceMesh& m = meshes.rock;
  for (auto& p : m.positions)
    if (p[2] > 3.99f && p[0] > 0.01f && p[0] < 4.99f) p[2] += float(0.02 * std::sin(3.1 * p[0]) * std::cos(2.3 * p[1]));
  computeNormals(m);
  const VoxelRock rock = voxelize(flatBox);
  makeSurfaceLook(meshes, stainOnly(rock));
  float top = 0.0f;
  std::size_t counted = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const auto& p = m.positions[v];
    if (p[2] > 3.9f && p[0] > 0.5f && p[0] < 4.5f && p[1] > 0.5f && p[1] < kWidth - 0.5f) {
      top = std::max(top, m.look[v][kStain]);
      ++counted;
    }
  }
  ASSERT_GT(counted, 1000u);
  EXPECT_LT(top, 0.03f);
}

// An overhang (its lip at x = 5, z = 4) over a recess, above a ledge at z ≈ 2 that reaches just
// past the lip (to x = 5.5) and tilts outwards; the top tilts towards the lip.
std::vector<Point2> overhang(double y) {
  (void)y;
  return {{0, 0}, {0, 6.5}, {5, 6}, {5, 4}, {2, 4}, {2, 2}, {5.5, 1.9}, {5.5, 0}};
}

TEST(Flow, WaterShedAtAnOverhangLipReachesTheSurfaceBelow) {
  AssetMeshes meshes;
  meshes.rock = sweep(overhang, 0.125);
  const VoxelRock rock = voxelize(overhang);
  makeSurfaceLook(meshes, stainOnly(rock));
  const SurfaceMesh& m = meshes.rock;
  const double mid = 0.5 * kWidth;
  // The lip sheds what ran off the top: the outer face of the overhang carries it ...
  EXPECT_GT(lookAt(m, kStain, 5.0, mid, 5.0), 0.5f);
  // ... and the ledge's face below it is stained by the drip, not by the little rain the
  // ledge's own open half-voxel catches (that alone would stain it about 0.1).
  EXPECT_GT(lookAt(m, kStain, 5.5, mid, 1.0), 0.35f);
  // The recess under the overhang stays dry and clean.
  EXPECT_LT(lookAt(m, kStain, 2.0, mid, 3.0), 0.05f);
  // The underside is a sheltered overhang: damper than the open top.
  EXPECT_GT(lookAt(m, kMoisture, 3.5, mid, 4.0), lookAt(m, kMoisture, 2.5, mid, 6.25) + 0.2f);
}

// Two steps: a top at z = 6 and a ledge at z = 3.
std::vector<Point2> steps(double y) {
  (void)y;
  return {{0, 0}, {0, 6}, {3, 6}, {3, 3}, {6, 3}, {6, 0}};
}

TEST(SurfaceLook, MoistureIsHighestAtTheFoot) {
  const double mid = 0.5 * kWidth;
  {  // On the ground.
    AssetMeshes meshes;
    meshes.rock = sweep(steps, 0.125);
    const VoxelRock rock = voxelize(steps, true);
    makeSurfaceLook(meshes, stainOnly(rock));
    const float foot = lookAt(meshes.rock, kMoisture, 6.0, mid, 0.25);
    EXPECT_GT(foot, 0.5f);
    EXPECT_GT(foot, 4.0f * lookAt(meshes.rock, kMoisture, 6.0, mid, 2.5));
    EXPECT_LT(lookAt(meshes.rock, kMoisture, 3.0, mid, 5.0), 0.05f);
  }
  {  // Free-floating, its foot in colluvium one voxel deep (z < 0.5) along the face at x = 6.
    AssetMeshes meshes;
    meshes.rock = sweep(steps, 0.125);
    VoxelRock rock = voxelize(steps, false);
    const GridLayout& g = rock.layout;
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (g.center(x, y, 0)[0] > 6.0 && g.center(x, y, 0)[0] < 8.0)
          rock.material[g.index(x, y, 0)] = Material::Colluvium;
    makeSurfaceLook(meshes, stainOnly(rock));
    const float foot = lookAt(meshes.rock, kMoisture, 6.0, mid, 0.75);
    EXPECT_GT(foot, 0.5f);
    EXPECT_GT(foot, 4.0f * lookAt(meshes.rock, kMoisture, 6.0, mid, 2.75));
  }
}

TEST(SurfaceLook, DustSettlesOnLedgesNotWalls) {
  AssetMeshes meshes;
  meshes.rock = sweep(steps, 0.125);
  const VoxelRock rock = voxelize(steps);
  SurfaceLookParams params = stainOnly(rock);
  makeSurfaceLook(meshes, params);
  const double mid = 0.5 * kWidth;
  const float ledge = lookAt(meshes.rock, kDust, 4.5, mid, 3.0), wall = lookAt(meshes.rock, kDust, 6.0, mid, 1.5);
  EXPECT_GT(ledge, 0.5f);
  EXPECT_LT(wall, 0.05f);
  // The strength scales it; 0 turns it off.
  params.dust = 0.0;
  makeSurfaceLook(meshes, params);
  EXPECT_EQ(lookAt(meshes.rock, kDust, 4.5, mid, 3.0), 0.0f);
}

TEST(SurfaceLook, AgeIsExposureScarsAreYoungAndVarnishNeedsTime) {
  AssetMeshes meshes;
  meshes.rock = sweep(steps, 0.25);
  SurfaceMesh& m = meshes.rock;
  for (std::size_t v = 0; v < m.positions.size(); ++v) m.history[v] = {0.7f, v % 2 ? 0.9f : 0.0f, 0.0f};
  const VoxelRock rock = voxelize(steps);
  SurfaceLookParams params;
  params.rock = &rock;
  makeSurfaceLook(meshes, params);
  for (std::size_t v = 0; v < m.positions.size(); ++v) ASSERT_NEAR(m.look[v][kAge], v % 2 ? 0.1f : 0.7f, 1e-6f);
  // Varnish grows with the exposure age: the same rock, young everywhere, is lighter.
  const std::vector<std::array<float, 4>> old_look = m.look;
  for (auto& h : m.history) h = {0.05f, 0.0f, 0.0f};
  makeSurfaceLook(meshes, params);
  double old_g = 0, young_g = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) old_g += old_look[v][kStain], young_g += m.look[v][kStain];
  EXPECT_GT(old_g, 1.5 * young_g);
  // Time against colluvium is not all time in the open: the same old rock, with a face on
  // colluvium the whole run, is lighter.
  const auto total_g = [&](float burial) {
    for (auto& h : m.history) h = {1.0f, 0.0f, burial};
    makeSurfaceLook(meshes, params);
    double g = 0;
    for (const auto& l : m.look) g += l[kStain];
    return g;
  };
  EXPECT_LT(total_g(1.0f), 0.9 * total_g(0.0f));
}

TEST(SurfaceLook, ColluviumIsDampAtTheRockAndUnaged) {
  AssetMeshes meshes;
  meshes.rock = sweep(steps, 0.25);
  VoxelRock rock = voxelize(steps, true);
  // A strip of colluvium surface on the ground beside the face at x = 6, out to x = 8.5.
  SurfaceMesh& c = meshes.colluvium;
  c.name = "colluvium";
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 10; ++i) c.positions.push_back({float(6.0 + 0.25 * i), float(j), float(0.9 - 0.09 * i)});
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 10; ++i) {
      const std::uint32_t a = std::uint32_t(i + 11 * j);
      c.triangles.push_back({a, a + 1, a + 11});
      c.triangles.push_back({a + 1, a + 12, a + 11});
    }
  computeNormals(c);
  makeSurfaceLook(meshes, stainOnly(rock));
  ASSERT_EQ(c.look.size(), c.positions.size());
  const float at_rock = lookAt(c, kMoisture, 6.0, 4.0, 0.9), away = lookAt(c, kMoisture, 7.25, 4.0, 0.4);
  EXPECT_GT(at_rock, 0.3f);
  EXPECT_GT(at_rock, away);
  for (const auto& l : c.look) EXPECT_EQ(l[kAge] + l[kStain] + l[kDust], 0.0f);
}

// A bumpy version of the overhang, with drips, pits and streaks: the result is byte-identical
// with one thread and with two.
TEST(SurfaceLook, SameAtAnyThreadCount) {
  AssetMeshes meshes;
  meshes.rock = sweep(overhang, 0.05);
  SurfaceMesh& m = meshes.rock;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    auto& p = m.positions[v];
    p[0] += float(0.04 * std::sin(7.0 * p[1] + 3.0 * p[2]));
    p[2] += float(0.03 * std::cos(5.0 * p[1] - 2.0 * p[0]));
    m.history[v] = {float(0.5 + 0.5 * std::sin(double(v))), float(v % 7 == 0 ? 0.5 : 0.0), 0.0f};
    m.curvature[v] = float(0.5 + 0.4 * std::sin(0.37 * double(v)));
  }
  computeNormals(m);
  ASSERT_GT(m.positions.size(), 40000u);
  const VoxelRock rock = voxelize(overhang);
  SurfaceLookParams params;
  params.rock = &rock;
  const auto run = [&] {
    AssetMeshes copy = meshes;
    makeSurfaceLook(copy, params);
    return copy.rock.look;
  };
  std::vector<std::array<float, 4>> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = run();
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = run();
  }
  ASSERT_EQ(one.size(), m.positions.size());
  ASSERT_EQ(two.size(), one.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(one[0])), 0);
  // Something was computed: stains, damp and dust all occur.
  float most[4] = {0, 0, 0, 0};
  for (const auto& l : one)
    for (int k = 0; k < 4; ++k) most[k] = std::max(most[k], l[k]);
  for (int k = 0; k < 4; ++k) EXPECT_GT(most[k], 0.3f) << "channel " << k;
}

TEST(SurfaceLook, AMeshWithoutHistoryGetsNoLook) {
  AssetMeshes meshes;
  meshes.rock = sweep(steps, 0.25);
  meshes.rock.history.clear();
  meshes.colluvium = sweep(flatBox, 0.5);
  meshes.colluvium.history.clear();
  const AssetMeshes before = meshes;
  makeSurfaceLook(meshes, {});  // no grid needed: nothing is read
  EXPECT_TRUE(meshes.rock.look.empty());
  EXPECT_TRUE(meshes.colluvium.look.empty());
  EXPECT_EQ(meshes.rock.positions, before.rock.positions);
  EXPECT_EQ(meshes.rock.normals, before.rock.normals);
  EXPECT_EQ(meshes.colluvium.positions, before.colluvium.positions);
  // With a history, the grid is required.
  meshes.rock.history.assign(meshes.rock.positions.size(), {1.0f, 0.0f, 0.0f});
  EXPECT_THROW(makeSurfaceLook(meshes, {}), std::invalid_argument);
}

}  // namespace
}  // namespace rockbake
