// Families (docs/model.md §12): the aligned-IoU measure on shapes worked out by
// hand, the draw's determinism, and the catalogue families keeping each kind
// itself at every seed.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>
#include <tuple>

#include "inputs/resolve_shape.h"
#include "preset/load_preset.h"
#include "sim/family.h"
#include "sim/grid_layout.h"
#include "sim/rock_measures.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

// A rock of the voxels of edge h whose centres `inside` holds, in a grid of n voxels a side.
VoxelRock voxelized(int nx, int ny, int nz, double h, const std::function<bool(const Vec3d&)>& inside) {
  VoxelRock rock;
  rock.layout.nx = nx, rock.layout.ny = ny, rock.layout.nz = nz, rock.layout.h = h;
  rock.layout.origin = {-nx * h / 2, -ny * h / 2, 0.0};
  rock.material.assign(rock.layout.cellCount(), Material::Air);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        if (inside(rock.layout.center(x, y, z))) rock.material[rock.layout.index(x, y, z)] = Material::Rock;
  return rock;
}

// An L-shaped block with a bump: no symmetry a turn or a mirror could hide.
bool lShape(const Vec3d& p) {
  const bool foot = p[0] > -1.0 && p[0] < 1.0 && p[1] > -0.6 && p[1] < 0.0 && p[2] < 0.8;
  const bool leg = p[0] > -1.0 && p[0] < -0.4 && p[1] >= 0.0 && p[1] < 1.2 && p[2] < 0.8;
  const bool bump = std::hypot(p[0] - 0.6, p[1] + 0.3) < 0.25 && p[2] < 1.3;
  return foot || leg || bump;
}

TEST(AlignedIoU, AShapeAgainstItselfTurnedAndMirroredIsOne) {
  const VoxelRock a = voxelized(60, 60, 40, 0.05, lShape);
  // Turned 90° counter-clockwise and mirrored in x, in a grid of another size.
  const VoxelRock b = voxelized(70, 64, 44, 0.05, [](const Vec3d& p) { return lShape({p[1], p[0], p[2]}); });
  EXPECT_NEAR(alignedIoU(a, b), 1.0, 1e-9);
  EXPECT_NEAR(alignedIoU(b, a), 1.0, 1e-9);
  // Twice the size: scaled to equal volume, the same shape again (up to the voxels).
  const VoxelRock c = voxelized(120, 120, 60, 0.05, [](const Vec3d& p) {
    return lShape({-p[0] / 2, p[1] / 2, p[2] / 2});
  });
  EXPECT_GT(alignedIoU(a, c), 0.95);
}

TEST(AlignedIoU, TwoSpheroidsGiveTheValueWorkedOutByHand) {
  // Both of volume 8π/3, resting on the ground: radii (1, 1, 2) standing and
  // (√2, √2, 1) squat. Their circular sections are r₁² = z − z²/4 and
  // r₂² = 4z − 2z²; the first is the smaller below z = 12/7, so
  //   I = π (∫₀^{12/7} z − z²/4 dz + ∫_{12/7}^2 4z − 2z² dz) = π (360/343 + 152/1029) = 1232π/1029,
  // I / V = 22/49, and IoU = I / (2V − I) = 22 / 76 = 11/38 ≈ 0.2895, whatever the turn.
  const double h = 0.04;
  const VoxelRock standing = voxelized(
      56, 56, 104, h, [](const Vec3d& p) { return p[0] * p[0] + p[1] * p[1] + (p[2] - 2) * (p[2] - 2) / 4 <= 1; });
  const VoxelRock squat = voxelized(
      76, 76, 56, h, [](const Vec3d& p) { return (p[0] * p[0] + p[1] * p[1]) / 2 + (p[2] - 1) * (p[2] - 1) <= 1; });
  EXPECT_NEAR(alignedIoU(standing, squat), 11.0 / 38.0, 0.01);
  // And two boxes, 2 × 1 × 1 lying against 1 × 1 × 2 standing: the best pose
  // shares a 1 × 1 × 1 cube, so IoU = 1 / (2 + 2 − 1) = 1/3.
  const VoxelRock lying = voxelized(
      60, 60, 30, 0.05, [](const Vec3d& p) { return std::abs(p[0]) < 1 && std::abs(p[1]) < 0.5 && p[2] < 1; });
  const VoxelRock upright = voxelized(
      60, 60, 50, 0.05, [](const Vec3d& p) { return std::abs(p[0]) < 0.5 && std::abs(p[1]) < 0.5 && p[2] < 2; });
  EXPECT_NEAR(alignedIoU(lying, upright), 1.0 / 3.0, 0.01);
}

TEST(PrincipalAxes, ABoxsAxesAreItsSidesOverRootTwelve) {
  const VoxelRock box = voxelized(
      100, 60, 30, 0.05, [](const Vec3d& p) { return std::abs(p[0]) < 2 && std::abs(p[1]) < 1 && p[2] < 0.5; });
  const auto axes = principalAxes(box);
  EXPECT_NEAR(axes[0], 4 / std::sqrt(12.0), 0.01);
  EXPECT_NEAR(axes[1], 2 / std::sqrt(12.0), 0.01);
  EXPECT_NEAR(axes[2], 0.5 / std::sqrt(12.0), 0.01);
}

// kSmallPreset (a box) with a family.
std::string familyPreset(const std::string& family) {
  return std::string(test::kSmallPreset) + "family: " + family + "\n";
}

TEST(Family, EachSeedDrawsItsOwnIndividualAndTheSameSeedTheSameOne) {
  const std::string text = familyPreset(
      "{scale: [0.7, 1.4], stretch: [[0.7, 1.4], [0.7, 1.4], [0.8, 1.2]], tilt: 8, "
      "warp: {bend: 0.2, taper: 0.3, twist: 30}}");
  std::set<std::tuple<double, double, double>> seen;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const Preset p = parsePreset(text, "family.yaml", {{}, seed, std::nullopt});
    const Individual a = drawIndividual(p), b = drawIndividual(p);
    EXPECT_TRUE(a.drawn);
    EXPECT_EQ(a.scale, b.scale);
    EXPECT_EQ(a.domain, b.domain);
    EXPECT_GE(a.scale, 0.7);
    EXPECT_LE(a.scale, 1.4);
    EXPECT_LE(a.tilt, 8.0);
    seen.insert({a.scale, a.stretch[0], a.azimuth});
  }
  EXPECT_EQ(seen.size(), 8u);
}

TEST(Family, TheBlockoutMapsBackExactly) {
  const Preset p =
      parsePreset(familyPreset("{scale: [0.7, 1.4], stretch: [[0.7, 1.4], [0.7, 1.4], [0.8, 1.2]], tilt: 20, "
                               "warp: {bend: 0.3, taper: 0.5, twist: 90}}"),
                  "family.yaml", {{}, 5, std::nullopt});
  const Individual ind = drawIndividual(p);
  // The individual's grid holds the whole blockout: its corners come back inside grid.size's box.
  const GridLayout g = computeGridLayout(p);
  EXPECT_NEAR(g.h, 2.0 / 24, 1e-12);  // the voxel size stays the preset's
  const VoxelRock rock = buildInitialRock(resolveShape(p), p);
  ASSERT_GT(rock.count(Material::Rock), 0u);
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] == Material::Rock) {
          const Vec3d q = toBlockout(ind, p, g.center(x, y, z));
          EXPECT_LE(std::abs(q[0] - 1.0), 0.75 + 1e-9);
          EXPECT_LE(std::abs(q[1] - 1.0), 0.75 + 1e-9);
          EXPECT_LE(q[2], 1.5 + 1e-9);
        }
}

TEST(Family, WithoutAFamilyTheGridAndRockAreThePresetsOwn) {
  const Preset p = parsePreset(test::kSmallPreset, "small.yaml");
  const Individual ind = drawIndividual(p);
  EXPECT_FALSE(ind.drawn);
  EXPECT_EQ(ind.domain, p.grid.size);
  const Vec3d q{0.3, 1.7, 0.9};
  EXPECT_EQ(toBlockout(ind, p, q), q);
}

TEST(Family, FractureCutsAlongTheJointSets) {
  const std::string text = std::string(test::kSmallPreset) +
                           "durability:\n  joints:\n    - {strike: 30, dip: 80, spacing: 0.5, width: 0.05, factor: 1}\n"
                           "family: {fracture: {cuts: [1, 1], depth: [0.3, 0.3]}}\n";
  const Preset p = parsePreset(text, "cut.yaml", {{}, 4, std::nullopt});
  const Individual ind = drawIndividual(p);
  ASSERT_EQ(ind.cuts.size(), 1u);
  const VoxelRock cut = buildInitialRock(resolveShape(p), p);
  Preset whole = p;
  whole.family->fracture.reset();
  const VoxelRock uncut = buildInitialRock(resolveShape(whole), whole);
  // A third of the block's width along the normal is taken: about a fifth to
  // two fifths of the volume, depending on the plane's angle to the box.
  const double kept = double(cut.count(Material::Rock)) / double(uncut.count(Material::Rock));
  EXPECT_GT(kept, 0.55);
  EXPECT_LT(kept, 0.85);
  // The plane's normal is the joint set's (strike 30° turned with the azimuth, dip 80°): nearly horizontal.
  EXPECT_LT(std::abs(ind.cuts[0].normal[2]), std::sin(10.5 * M_PI / 180));
}

// ---- the catalogue's families keep each kind itself ----

constexpr int kSeeds = 8;

VoxelRock weathered(const std::string& preset, std::uint64_t seed, int resolution) {
  const Preset p = loadPreset(test::sourceDir() / "presets" / preset, {{}, seed, resolution});
  return weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
}

double graphAt(const Preset& p, double a) {
  const auto& pts = p.durability.graph.points;
  if (a <= pts.front()[0]) return pts.front()[1];
  for (std::size_t i = 1; i < pts.size(); ++i)
    if (a <= pts[i][0])
      return pts[i - 1][1] + (a - pts[i - 1][0]) / (pts[i][0] - pts[i - 1][0]) * (pts[i][1] - pts[i - 1][1]);
  return pts.back()[1];
}

// The weathered profile against the durability graph, between the altitudes
// where more than the graph shapes the rock (the foot's apron, the rounded top).
double profileCorrelation(const std::string& preset, std::uint64_t seed, int resolution, double from, double to) {
  const Preset p = loadPreset(test::sourceDir() / "presets" / preset, {{}, seed, resolution});
  const VoxelRock rock = weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
  const std::vector<double> radii = test::layerRadii(rock);
  std::vector<double> r, d;
  for (int z = 0; z < rock.layout.nz; ++z) {
    const double a = rock.layout.altitude(z);
    if (a < from || a > to || radii[std::size_t(z)] == 0) continue;
    r.push_back(radii[std::size_t(z)]);
    d.push_back(graphAt(p, a));
  }
  return test::pearson(r, d);
}

// Compared between the apron (which shields the foot: goblin keeps all its
// debris) and the top (rounded from above by spheroidal weathering, and on the
// column softened by its keyframe): the band where the beds decide the shape.
TEST(CatalogueFamilies, LayeredProfilesFollowTheirGraphsAtEverySeed) {
  for (int s = 0; s < kSeeds; ++s) {
    EXPECT_GE(profileCorrelation("layered-column.yaml", 11 + std::uint64_t(s), 48, 0.15, 0.72), 0.85)
        << "layered-column seed " << 11 + s;
    EXPECT_GE(profileCorrelation("goblin.yaml", 7 + std::uint64_t(s), 48, 0.3, 0.75), 0.85) << "goblin seed " << 7 + s;
  }
}

// The Euler characteristic of the rock standing on the ground (a slab one
// voxel deep under the whole grid) as a union of closed cubes: V − E + F − C of
// the cubical complex. A connected solid without cavities has χ = 1 − genus;
// an arch's opening is closed by the ground, so the ground counts.
long long eulerCharacteristic(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  const auto solid = [&](int x, int y, int z) {
    if (z == -1) return x >= 0 && y >= 0 && x < g.nx && y < g.ny;
    return g.contains(x, y, z) && rock.material[g.index(x, y, z)] == Material::Rock;
  };
  // A lattice point, edge or face belongs to the complex when any voxel touching it is rock.
  const auto anyOf = [&](int x, int y, int z, int dx, int dy, int dz) {
    for (int i = 0; i <= dx; ++i)
      for (int j = 0; j <= dy; ++j)
        for (int k = 0; k <= dz; ++k)
          if (solid(x - i, y - j, z - k)) return true;
    return false;
  };
  long long chi = 0;
  for (int z = -1; z <= g.nz; ++z)
    for (int y = 0; y <= g.ny; ++y)
      for (int x = 0; x <= g.nx; ++x) {
        chi += anyOf(x, y, z, 1, 1, 1);                                                      // vertices
        chi -= anyOf(x, y, z, 0, 1, 1) + anyOf(x, y, z, 1, 0, 1) + anyOf(x, y, z, 1, 1, 0);  // edges
        chi += anyOf(x, y, z, 0, 0, 1) + anyOf(x, y, z, 0, 1, 0) + anyOf(x, y, z, 1, 0, 0);  // faces
        chi -= solid(x, y, z);                                                               // cubes
      }
  return chi;
}

// Pieces of the rock standing on the ground, as closed cubes touch (26-connected), the ground one piece.
long long piecesOnTheGround(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::vector<std::uint8_t> seen(g.cellCount(), 0);
  long long pieces = 1;  // the ground and all that touches it
  std::vector<std::size_t> stack;
  const auto flood = [&](std::size_t start) {
    stack.assign(1, start);
    seen[start] = 1;
    while (!stack.empty()) {
      const VoxelCoord c = g.coord(stack.back());
      stack.pop_back();
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = c.x + dx, y = c.y + dy, z = c.z + dz;
            if (!g.contains(x, y, z)) continue;
            const std::size_t i = g.index(x, y, z);
            if (!seen[i] && rock.material[i] == Material::Rock) seen[i] = 1, stack.push_back(i);
          }
    }
  };
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x)
      if (rock.material[g.index(x, y, 0)] == Material::Rock && !seen[g.index(x, y, 0)]) flood(g.index(x, y, 0));
  for (std::size_t i = 0; i < g.cellCount(); ++i)
    if (rock.material[i] == Material::Rock && !seen[i]) flood(i), ++pieces;
  return pieces;
}

TEST(CatalogueFamilies, TheArchKeepsItsOpeningAtEverySeed) {
  for (int s = 0; s < kSeeds; ++s) {
    const VoxelRock rock = weathered("arch.yaml", 31 + std::uint64_t(s), 48);
    // χ = pieces − handles (no cavities in a weathered rock): at least one handle through the opening.
    const long long handles = piecesOnTheGround(rock) - eulerCharacteristic(rock);
    EXPECT_GE(handles, 1) << "arch seed " << 31 + s << ": no through-hole";
  }
}

TEST(CatalogueFamilies, TheHoodoosCapStaysWiderThanItsNeck) {
  for (int s = 0; s < kSeeds; ++s) {
    const VoxelRock rock = weathered("hoodoo-cap.yaml", 21 + std::uint64_t(s), 48);
    const std::vector<double> radii = test::layerRadii(rock);
    double neck = 1e9, cap = 0;
    for (int z = 0; z < rock.layout.nz; ++z) {
      const double a = rock.layout.altitude(z);
      if (a > 0.5 && a < 0.68) neck = std::min(neck, radii[std::size_t(z)]);
      if (a > 0.78 && a < 0.9) cap = std::max(cap, radii[std::size_t(z)]);
    }
    EXPECT_GT(cap, neck * 1.15) << "hoodoo-cap seed " << 21 + s;
  }
}

}  // namespace
}  // namespace rockbake
