// Surface detail made by the weathering processes (mesh/surface_detail.h): laminations whose ridges
// follow the beds' strike and whose harder laminae stand out, exfoliation sheets stepping where
// the exposure age crosses a sheet boundary on convex rock, pits in concave rock; the ground cap
// kept; without a process, exactly the noise alone; the same bytes at any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include <tbb/global_control.h>

#include "core/hash.h"
#include "core/surface_mesh.h"
#include "core/vec3.h"
#include "mesh/surface_detail.h"

namespace rockbake {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Uniform attributes: durability ½ of 0..1 (softness ½), bare rock, exposure s.
void fillAttributes(SurfaceMesh& mesh, float s) {
  const std::size_t n = mesh.positions.size();
  mesh.durability.assign(n, 0.5f);
  mesh.colluvium.assign(n, 0.0f);
  mesh.curvature.assign(n, s);
  mesh.altitude.assign(n, 0.5f);
}

// A vertical face in the plane y = 0, facing −y: x in [0, width], z in [z0, z0 + width], `cells`
// squares a side.
SurfaceMesh verticalFace(double width, double z0, int cells) {
  SurfaceMesh mesh;
  mesh.name = "rock";
  const int m = cells + 1;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      mesh.positions.push_back({float(width * i / cells), 0.0f, float(z0 + width * j / cells)});
      mesh.normals.push_back({0.0f, -1.0f, 0.0f});
    }
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const std::uint32_t a = j * m + i, b = a + 1, c = a + m, d = c + 1;
      mesh.triangles.push_back({a, b, c});  // (x, z) counter-clockwise seen from −y
      mesh.triangles.push_back({b, d, c});
    }
  fillAttributes(mesh, 0.5f);
  return mesh;
}

// A sphere of `radius` about `centre`: an icosahedron split `levels` times, radial normals.
SurfaceMesh icosphere(const Vec3d& centre, double radius, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3d> p{{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<std::uint32_t, 3>> tris{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& v : p) v = normalised(v, Vec3d{0, 0, 1});
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    const auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto [it, fresh] = middle.try_emplace({key.first, key.second}, std::uint32_t(p.size()));
      if (fresh) p.push_back(normalised(add(p[a], p[b]), Vec3d{0, 0, 1}));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& [a, b, c] : tris) {
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    tris = std::move(next);
  }
  SurfaceMesh mesh;
  mesh.name = "rock";
  for (const auto& v : p) {
    mesh.positions.push_back(toVec3f(add(centre, scale(v, radius))));
    mesh.normals.push_back(toVec3f(v));
  }
  mesh.triangles = tris;
  fillAttributes(mesh, 0.5f);
  return mesh;
}

// Each vertex's move along its normal before the displacement.
std::vector<double> displacement(const SurfaceMesh& before, const SurfaceMesh& after) {
  std::vector<double> d(before.positions.size());
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = dot(sub(toVec3d(after.positions[i]), toVec3d(before.positions[i])), toVec3d(before.normals[i]));
  return d;
}

SurfaceMesh displaced(const SurfaceMesh& mesh, const DetailParams& params) {
  SurfaceMesh out = mesh;
  displaceSurface(out, params);
  return out;
}

// The unit normal of beds striking at `strike` (from +x towards +y) and dipping `dip`.
Vec3d bedNormal(double strike, double dip) {
  const Vec3d dip_direction{-std::sin(strike), std::cos(strike), 0.0};  // horizontal, down the dip
  return add(scale(Vec3d{0, 0, 1}, std::cos(dip)), scale(dip_direction, -std::sin(dip)));
}

// The direction in the face's (x, z) plane, radians from +x, of the principal axis of the
// displacement gradients' structure tensor over the vertical face.
double dominantGradientAngle(const SurfaceMesh& face, const std::vector<double>& d) {
  double sxx = 0, sxz = 0, szz = 0;
  for (const auto& [a, b, c] : face.triangles) {
    const auto& pa = face.positions[a];
    const double e1x = face.positions[b][0] - pa[0], e1z = face.positions[b][2] - pa[2];
    const double e2x = face.positions[c][0] - pa[0], e2z = face.positions[c][2] - pa[2];
    const double d1 = d[b] - d[a], d2 = d[c] - d[a], det = e1x * e2z - e1z * e2x;
    const double gx = (d1 * e2z - d2 * e1z) / det, gz = (e1x * d2 - e2x * d1) / det;
    sxx += gx * gx, sxz += gx * gz, szz += gz * gz;
  }
  return 0.5 * std::atan2(2 * sxz, sxx - szz);
}

// The angle between two lines in a plane (radians from +x), 0..90 degrees.
double lineAngleDegrees(double a, double b) {
  double d = std::fmod(std::abs(a - b), std::numbers::pi);
  return std::min(d, std::numbers::pi - d) / kDegree;
}

DetailParams laminated(double amplitude, double noise) {
  DetailParams params;
  params.noise = NoiseParams{noise, 0.3, 3};
  params.seed = 17;
  params.ground = false;
  params.processes.laminations = {amplitude, 0.08};
  return params;
}

// ---- laminations ----

// On a vertical face, beds striking at 60° and dipping 30° cut the face along lines tilted 27°
// from the horizontal: the relief's gradients point along the beds' normal's trace on the face,
// so its ridges follow the strike; flat beds give horizontal ridges. The noise under it does not
// hide that.
TEST(SurfaceDetailLaminations, RidgesFollowTheBedsStrike) {
  const SurfaceMesh face = verticalFace(2.0, 0.5, 200);
  for (const double dip : {30.0, 0.0}) {
    SCOPED_TRACE(dip);
    const Vec3d n_bed = bedNormal(60 * kDegree, dip * kDegree);
    DetailParams params = laminated(0.01, 0.003);
    params.processes.bed_position = [n_bed](const Vec3d& p) { return dot(p, n_bed); };
    const auto d = displacement(face, displaced(face, params));
    const double expected = std::atan2(n_bed[2], n_bed[0]);  // the normal's trace on the face
    EXPECT_LT(lineAngleDegrees(dominantGradientAngle(face, d), expected), 15.0);
    // The test can tell: the dipping beds' trace is well off the vertical.
    if (dip > 0)
      EXPECT_GT(lineAngleDegrees(expected, std::numbers::pi / 2), 20.0);
    else
      EXPECT_LT(lineAngleDegrees(dominantGradientAngle(face, d), std::numbers::pi / 2), 15.0);
  }
  // Without a bed position the beds are flat: horizontal ridges.
  const auto d = displacement(face, displaced(face, laminated(0.01, 0.003)));
  EXPECT_LT(lineAngleDegrees(dominantGradientAngle(face, d), std::numbers::pi / 2), 5.0);
}

// Mid-lamina (away from any parting, however the partings are shifted), each lamina's face stands
// out with its seeded hardness: harder laminae outward, softer ones etched back. Soft rock shows
// its beds more than hard rock.
TEST(SurfaceDetailLaminations, HarderLaminaeStandOut) {
  SurfaceMesh face = verticalFace(2.0, 0.5, 200);
  const DetailParams params = laminated(0.01, 0.0);
  const auto d = displacement(face, displaced(face, params));
  std::map<std::int64_t, std::pair<double, int>> lamina;  // index: (sum of displacement, count)
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double b = face.positions[i][2] / 0.08, t = b - std::floor(b);
    if (t < 0.45 || t > 0.55) continue;
    auto& [sum, count] = lamina[std::int64_t(std::floor(b))];
    sum += d[i], ++count;
  }
  ASSERT_GT(lamina.size(), 20u);
  double hard = 0, soft = 0, sh = 0, sd = 0, shh = 0, sdd = 0, shd = 0;
  int hard_n = 0, soft_n = 0;
  for (const auto& [k, sum_count] : lamina) {
    const double h = unitInterval(counterHash(params.seed, purposeId("laminae"), 0, std::uint64_t(k)));
    const double mean = sum_count.first / sum_count.second;
    (h > 0.5 ? hard : soft) += mean;
    ++(h > 0.5 ? hard_n : soft_n);
    sh += h, sd += mean, shh += h * h, sdd += mean * mean, shd += h * mean;
  }
  ASSERT_GT(hard_n, 3);
  ASSERT_GT(soft_n, 3);
  EXPECT_GT(hard / hard_n - soft / soft_n, 0.4 * 0.01);
  const double m = double(lamina.size());
  const double correlation = (shd - sh * sd / m) / std::sqrt((shh - sh * sh / m) * (sdd - sd * sd / m));
  EXPECT_GT(correlation, 0.95);

  // Soft rock (durability at the range's bottom) against hard (at its top): three times the relief.
  const auto rms = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x * x;
    return std::sqrt(s / double(v.size()));
  };
  face.durability.assign(face.positions.size(), 0.0f);
  const double soft_rms = rms(displacement(face, displaced(face, params)));
  face.durability.assign(face.positions.size(), 1.0f);
  const double hard_rms = rms(displacement(face, displaced(face, params)));
  EXPECT_NEAR(soft_rms / hard_rms, 3.0, 0.01);
}

// ---- exfoliation ----

// A convex (s 0.9) half and a concave (s 0.3) half of a sphere, its exposure age falling from +x
// to −x, so the depth the run retreated crosses nine sheet boundaries. On the convex half the
// surface stands proud towards each boundary and drops across it (a sawtooth of the depth over
// the sheets): the steepest relief sits at the boundaries. The concave half does not move.
TEST(SurfaceDetailExfoliation, StepsAtSheetBoundariesOnConvexRockOnly) {
  SurfaceMesh sphere = icosphere({0, 0, 2}, 1.0, 6);
  const std::size_t n = sphere.positions.size();
  const double spacing = 0.1, retreat = 1.0, amplitude = 0.01;
  std::vector<double> sheets(n);  // the depth in sheets, without the boundaries' jitter
  sphere.history.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double age = 0.5 + 0.45 * sphere.positions[i][0];
    sphere.history[i] = {float(age), 0.0f, 0.0f};
    sphere.curvature[i] = sphere.positions[i][1] > 0 ? 0.9f : 0.3f;
    sheets[i] = (1.0 - sphere.history[i][0]) * retreat / spacing;
  }
  DetailParams params;
  params.noise = NoiseParams{0.0, 0.08, 3};
  params.seed = 5;
  params.ground = false;
  params.processes.exfoliation = {amplitude, spacing};
  params.processes.retreat = retreat;
  const auto d = displacement(sphere, displaced(sphere, params));

  double late = 0, early = 0;  // mean relief late in a sheet (near its outer boundary) and early
  int late_n = 0, early_n = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (sphere.curvature[i] < 0.5f) {
      EXPECT_EQ(d[i], 0.0) << "concave vertex " << i;
      continue;
    }
    const double f = sheets[i] - std::floor(sheets[i]);
    if (f > 0.55 && f < 0.75) late += d[i], ++late_n;
    if (f > 0.1 && f < 0.3) early += d[i], ++early_n;
    EXPECT_GE(d[i], -1e-6);
    EXPECT_LE(d[i], amplitude + 1e-6);
  }
  ASSERT_GT(late_n, 1000);
  ASSERT_GT(early_n, 1000);
  EXPECT_GT(late / late_n - early / early_n, 0.3 * amplitude);

  // The steepest twentieth of the convex edges lie at sheet boundaries (within a quarter sheet of
  // one, which half the surface is).
  std::vector<std::pair<double, double>> slopes;  // (slope, sheets at the edge's middle)
  for (const auto& t : sphere.triangles)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = t[c], b = t[(c + 1) % 3];
      if (a > b || sphere.curvature[a] < 0.5f || sphere.curvature[b] < 0.5f) continue;
      const double length = std::sqrt(distanceSquared(toVec3d(sphere.positions[a]), toVec3d(sphere.positions[b])));
      slopes.push_back({std::abs(d[a] - d[b]) / length, 0.5 * (sheets[a] + sheets[b])});
    }
  std::sort(slopes.begin(), slopes.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  const std::size_t top = slopes.size() / 20;
  std::size_t at_boundary = 0;
  for (std::size_t e = 0; e < top; ++e)
    if (std::abs(slopes[e].second - std::round(slopes[e].second)) < 0.25) ++at_boundary;
  EXPECT_GT(double(at_boundary), 0.9 * double(top));

  // Without a history there are no exposure ages: no sheets.
  sphere.history.clear();
  const SurfaceMesh bare = displaced(sphere, params);
  EXPECT_EQ(bare.positions, sphere.positions);
}

// ---- pitting ----

// Pits hollow the concave half (s 0.2) of a sphere, inward only; the convex half (s 0.8) keeps
// its surface.
TEST(SurfaceDetailPitting, PitsConcaveRockOnly) {
  SurfaceMesh sphere = icosphere({0, 0, 2}, 1.0, 6);
  const std::size_t n = sphere.positions.size();
  for (std::size_t i = 0; i < n; ++i) sphere.curvature[i] = sphere.positions[i][1] > 0 ? 0.8f : 0.2f;
  DetailParams params;
  params.noise = NoiseParams{0.0, 0.08, 3};
  params.seed = 9;
  params.ground = false;
  const double amplitude = 0.01;
  params.processes.pitting = {amplitude, 0.1};
  const auto d = displacement(sphere, displaced(sphere, params));
  std::size_t concave = 0, pitted = 0;
  double deepest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (sphere.curvature[i] > 0.5f) {
      EXPECT_EQ(d[i], 0.0) << "convex vertex " << i;
      continue;
    }
    ++concave;
    EXPECT_LE(d[i], 1e-7) << "a pit pushed vertex " << i << " out";
    if (d[i] < -0.1 * amplitude) ++pitted;
    deepest = std::min(deepest, d[i]);
  }
  EXPECT_GT(double(pitted), 0.1 * double(concave));
  EXPECT_LT(double(pitted), 0.6 * double(concave));  // pits, not a lowered surface
  EXPECT_LT(deepest, -0.5 * amplitude);
}

// ---- the whole ----

DetailParams allProcesses() {
  DetailParams params;
  params.noise = NoiseParams{0.01, 0.08, 3};
  params.seed = 23;
  params.durability_min = 0.2f;
  params.durability_max = 1.4f;
  params.processes.laminations = {0.01, 0.08};
  params.processes.exfoliation = {0.01, 0.1};
  params.processes.pitting = {0.01, 0.06};
  const Vec3d n_bed = bedNormal(20 * kDegree, 25 * kDegree);
  params.processes.bed_position = [n_bed](const Vec3d& p) { return dot(p, n_bed); };
  params.processes.retreat = 0.8;
  return params;
}

// A sphere resting on the ground (its bottom flattened to z = 0) with varied attributes and a
// history, concave near the ground and convex above.
SurfaceMesh groundedRock() {
  SurfaceMesh mesh = icosphere({0, 0, 0.7}, 1.0, 5);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    auto& p = mesh.positions[i];
    if (p[2] <= 0.0f) p[2] = 0.0f, mesh.normals[i] = {0.0f, 0.0f, -1.0f};
    const double x = p[0], y = p[1], z = p[2];
    mesh.durability[i] = float(0.8 + 0.5 * std::sin(3 * x + 2 * y));
    mesh.colluvium[i] = float(std::clamp(0.3 - z, 0.0, 1.0));
    mesh.curvature[i] = float(z < 0.4 ? 0.25 : 0.5 + 0.4 * std::sin(5 * x) * std::cos(4 * y));
    mesh.history.push_back({float(0.5 + 0.4 * std::sin(2 * x + z)), 0.0f, 0.0f});
  }
  return mesh;
}

// The ground cap does not move and nothing goes below the ground, under every process at once.
TEST(SurfaceDetail, GroundCapHoldsUnderTheProcesses) {
  const SurfaceMesh rock = groundedRock();
  const SurfaceMesh out = displaced(rock, allProcesses());
  std::size_t cap = 0, near_ground_moved = 0;
  for (std::size_t i = 0; i < rock.positions.size(); ++i) {
    EXPECT_GE(out.positions[i][2], 0.0f);
    if (rock.positions[i][2] == 0.0f) {
      ++cap;
      EXPECT_EQ(out.positions[i], rock.positions[i]);
    } else if (rock.positions[i][2] < 0.4f && out.positions[i] != rock.positions[i]) {
      ++near_ground_moved;
    }
  }
  EXPECT_GT(cap, 100u);
  EXPECT_GT(near_ground_moved, 100u);
}

// "look: none": processes at amplitude 0 (whatever else they are given) are no processes at all,
// to the byte, and the noise alone is what it always was.
TEST(SurfaceDetail, ProcessesAtAmplitudeZeroAreTheNoiseAlone) {
  const SurfaceMesh rock = groundedRock();
  DetailParams plain = allProcesses();
  plain.processes = DetailProcesses{};
  DetailParams off = allProcesses();
  off.processes.laminations.amplitude = 0;
  off.processes.exfoliation.amplitude = 0;
  off.processes.pitting.amplitude = 0;
  ASSERT_FALSE(off.processes.any());
  const SurfaceMesh a = displaced(rock, plain), b = displaced(rock, off);
  ASSERT_NE(a.positions, rock.positions);  // the noise did move it
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(a.positions[0])));
  EXPECT_EQ(0, std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(a.normals[0])));
  // With a process on, the noise stays under it at kNoiseUnderProcesses of its amplitude: pits on
  // rock that is all convex (so none is dug) leave the noise alone, scaled. (Off the ground, and
  // grains coarse enough for the mesh that the fold-over guard stays out of it.)
  SurfaceMesh convex = icosphere({0, 0, 2}, 1.0, 5);
  convex.curvature.assign(convex.positions.size(), 0.8f);
  DetailParams coarse = plain, on = off;
  coarse.noise.period = on.noise.period = 0.4;
  coarse.ground = on.ground = false;
  on.processes.pitting.amplitude = 0.01;
  const auto noise = displacement(convex, displaced(convex, coarse));
  const auto under = displacement(convex, displaced(convex, on));
  double top = 0;
  for (std::size_t i = 0; i < noise.size(); ++i) {
    EXPECT_NEAR(under[i], kNoiseUnderProcesses * noise[i], 1e-6) << i;
    top = std::max(top, std::abs(noise[i]));
  }
  EXPECT_GT(top, 0.005);
  // No noise and no process: untouched, normals and all.
  DetailParams nothing = off;
  nothing.noise.amplitude = 0;
  const SurfaceMesh c = displaced(rock, nothing);
  EXPECT_EQ(c.positions, rock.positions);
  EXPECT_EQ(c.normals, rock.normals);
}

// Every process at once, on one thread and on two: the same bytes.
TEST(SurfaceDetail, ByteIdenticalAtAnyThreadCount) {
  const SurfaceMesh rock = groundedRock();
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    return displaced(rock, allProcesses());
  };
  const SurfaceMesh one = run(1), two = run(2);
  ASSERT_NE(one.positions, rock.positions);
  ASSERT_EQ(one.positions.size(), two.positions.size());
  EXPECT_EQ(0,
            std::memcmp(one.positions.data(), two.positions.data(), one.positions.size() * sizeof(one.positions[0])));
  EXPECT_EQ(0, std::memcmp(one.normals.data(), two.normals.data(), one.normals.size() * sizeof(one.normals[0])));
}

}  // namespace
}  // namespace rockbake
