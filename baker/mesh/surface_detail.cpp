#include "mesh/surface_detail.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/hash.h"
#include "core/perlin_noise.h"
#include "core/vec3.h"
#include "geometry/edge_table.h"
#include "geometry/triangle_geometry.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

// Laminae: each boundary (parting) moves by up to this share of the spacing, so laminae are 0.6 to
// 1.4 spacings thick. A lamina's face stands at kRidge · (2 hardness − 1) at its middle and rounds
// (a half sine across it) into the partings' groove at −kParting.
constexpr double kLaminaJitter = 0.2, kRidge = 0.7, kParting = 0.3;
// Exfoliation sheets: their boundaries wander by up to kSheetJitter sheets (Perlin noise of
// kSheetJitterPeriod spacings); the last kScarp of a sheet's width is its edge, falling off.
constexpr double kSheetJitter = 0.12, kSheetJitterPeriod = 3.0, kScarp = 0.12;
// Pits: kPitRadius spacings in radius (so `spacing` across), each 0.5 to 1 of the amplitude deep.
constexpr double kPitRadius = 0.5, kPitDepthMin = 0.5;

// Pairs of triangles across an edge that face the same side (by `normal`):
// on each edge, its faces in increasing order, each with the next.
std::vector<std::array<std::uint32_t, 2>> facingPairs(const SurfaceMesh& mesh, const std::vector<Vec3d>& normal) {
  const EdgeTable edges(mesh.triangles);
  std::vector<std::array<std::uint32_t, 2>> pairs;
  std::vector<std::uint32_t> faces;
  for (std::uint32_t e = 0; e < edges.edges().size(); ++e) {
    faces.clear();
    for (std::uint32_t c : edges.forwardCorners(e)) faces.push_back(edges.face(c));
    for (std::uint32_t c : edges.backwardCorners(e)) faces.push_back(edges.face(c));
    std::sort(faces.begin(), faces.end());
    for (std::size_t i = 0; i + 1 < faces.size(); ++i)
      if (dot(normal[faces[i]], normal[faces[i + 1]]) > 0) pairs.push_back({faces[i], faces[i + 1]});
  }
  return pairs;
}

bool onGroundCap(const SurfaceMesh& mesh, const DetailParams& params, std::size_t i) {
  return params.ground && mesh.positions[i][2] == 0.0f;
}

// 0 at x = from, 1 at x = to (either way round), Hermite in between.
double smoothstep(double from, double to, double x) {
  const double t = std::clamp((x - from) / (to - from), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

double exposure(const SurfaceMesh& mesh, std::size_t i) {
  return std::clamp(double(mesh.curvature[i]), 0.0, 1.0);
}

double uncovered(const SurfaceMesh& mesh, std::size_t i) {
  return 1.0 - std::clamp(double(mesh.colluvium[i]), 0.0, 1.0);
}

// (D_max − D) / (D_max − D_min) at vertex i, ½ when the range is empty.
double softness(const SurfaceMesh& mesh, const DetailParams& params, std::size_t i) {
  const double range = double(params.durability_max) - params.durability_min;
  return range > 0 ? std::clamp((double(params.durability_max) - mesh.durability[i]) / range, 0.0, 1.0) : 0.5;
}

// The seeded noise at `share` of its amplitude into `offset` (assigned, not added). False when it
// has nothing to give: no amplitude, or the noise is flat over these vertices.
bool addNoise(const SurfaceMesh& mesh, const DetailParams& params, double share, std::vector<double>& offset) {
  const std::size_t n = mesh.positions.size();
  if (params.noise.amplitude <= 0.0) return false;
  const PerlinNoise noise(counterHash(params.seed, purposeId("mesh-detail"), 0, 0));
  const double inv_period = 1.0 / params.noise.period;
  const int octaves = std::clamp(params.noise.octaves, 1, 8);

  std::vector<double> value(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const auto& p = mesh.positions[i];
    value[i] = noise.fractal(p[0] * inv_period, p[1] * inv_period, p[2] * inv_period, octaves);
  });
  // Serial sum: the same order on every run, so the RMS (and the mesh) is byte-identical.
  double sum2 = 0;
  for (double v : value) sum2 += v * v;
  const double rms = std::sqrt(sum2 / double(n));
  if (rms <= 0) return false;

  const double scale = share * params.noise.amplitude / rms;
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    if (onGroundCap(mesh, params, i)) return;  // the ground cap stays flat on the ground
    offset[i] = scale * value[i] * (0.5 + softness(mesh, params, i)) * (0.5 + exposure(mesh, i)) * uncovered(mesh, i);
  });
  return true;
}

// Laminations: differential erosion across the beds. Lamina k lies between partings k and k + 1,
// parting k at (k + a seeded shift) spacings along the beds' normal; its seeded hardness sets how
// far its face stands out (hard) or is etched back (soft), and its face rounds off into a groove
// at each parting. A function of the bed position alone, so the ridges run along the strike.
void addLaminations(const SurfaceMesh& mesh, const DetailParams& params, std::vector<double>& offset) {
  const LookRelief& relief = params.processes.laminations;
  if (relief.amplitude <= 0 || relief.spacing <= 0) return;
  const auto& bed = params.processes.bed_position;
  const std::uint64_t laminae = purposeId("laminae");
  const auto parting = [&](std::int64_t k) {
    return double(k) +
           kLaminaJitter * (2.0 * unitInterval(counterHash(params.seed, laminae, 1, std::uint64_t(k))) - 1.0);
  };
  tbb::parallel_for(std::size_t(0), mesh.positions.size(), [&](std::size_t i) {
    if (onGroundCap(mesh, params, i)) return;
    const Vec3d p = toVec3d(mesh.positions[i]);
    const double b = (bed ? bed(p) : p[2]) / relief.spacing;  // in spacings
    if (!(std::abs(b) < 1e15)) return;
    auto k = std::int64_t(std::floor(b));
    if (b < parting(k))
      --k;
    else if (b >= parting(k + 1))
      ++k;
    const double hardness = unitInterval(counterHash(params.seed, laminae, 0, std::uint64_t(k)));
    // Rounded across the whole lamina, not a flat face with a groove a vertex wide: on the refined
    // mesh (a few vertices a lamina) a narrow groove reads as a row of pits with no direction.
    const double across = (b - parting(k)) / (parting(k + 1) - parting(k));         // 0 … 1 through the lamina
    const double face = std::sin(std::numbers::pi * std::clamp(across, 0.0, 1.0));  // 0 at the partings
    const double profile = kRidge * (2.0 * hardness - 1.0) * face - kParting * (1.0 - face);
    offset[i] += relief.amplitude * profile * (0.5 + softness(mesh, params, i)) * uncovered(mesh, i);
  });
}

// A sheet's relief at `f` (0..1) across it from its inner boundary: proud in proportion to how
// much of the sheet the smooth retreat has cut through, then falling off across its edge.
double sheetProfile(double f) {
  constexpr double edge = 1.0 - kScarp;
  return f < edge ? f : edge * 0.5 * (1.0 + std::cos(std::numbers::pi * (f - edge) / kScarp));
}

// Exfoliation: the surface comes off in whole sheets parallel to it, so it stands at the last
// sheet boundary the retreat reached (depth (1 − age) × retreat) rather than at the retreat itself:
// a sawtooth of that depth over the sheets' thickness, on convex rock.
void addExfoliation(const SurfaceMesh& mesh, const DetailParams& params, std::vector<double>& offset) {
  const LookRelief& relief = params.processes.exfoliation;
  const double retreat = params.processes.retreat;
  if (relief.amplitude <= 0 || relief.spacing <= 0 || retreat <= 0) return;
  if (mesh.history.size() != mesh.positions.size()) return;  // no history: no exposure ages
  const PerlinNoise jitter(counterHash(params.seed, purposeId("exfoliation"), 0, 0));
  const double inv_period = 1.0 / (kSheetJitterPeriod * relief.spacing);
  tbb::parallel_for(std::size_t(0), mesh.positions.size(), [&](std::size_t i) {
    if (onGroundCap(mesh, params, i)) return;
    const double weight = smoothstep(0.5, 0.8, exposure(mesh, i)) * uncovered(mesh, i);
    if (weight <= 0) return;
    const auto& p = mesh.positions[i];
    const double age = std::clamp(double(mesh.history[i][0]), 0.0, 1.0);
    const double wander = kSheetJitter * jitter(p[0] * inv_period, p[1] * inv_period, p[2] * inv_period);
    const double sheets = std::max((1.0 - age) * retreat / relief.spacing + wander, 0.0);
    offset[i] += relief.amplitude * weight * sheetProfile(sheets - std::floor(sheets));
  });
}

// The pit nearest to `q` (in cells of the pits' spacing) among those whose centres lie within
// kPitRadius of it, a pit centred at a hashed point of each cell: its squared distance (infinite
// when there is none) and its hash. Only the cells that reach within kPitRadius are visited.
std::pair<double, std::uint64_t> nearestPit(std::uint64_t seed, const Vec3d& q) {
  constexpr std::uint64_t pits = purposeId("pits");
  std::array<std::int64_t, 3> from, to;
  for (int a = 0; a < 3; ++a)
    from[a] = std::int64_t(std::floor(q[a] - kPitRadius)), to[a] = std::int64_t(std::floor(q[a] + kPitRadius));
  double nearest = std::numeric_limits<double>::infinity();
  std::uint64_t pit = 0;
  for (std::int64_t z = from[2]; z <= to[2]; ++z)
    for (std::int64_t y = from[1]; y <= to[1]; ++y)
      for (std::int64_t x = from[0]; x <= to[0]; ++x) {
        const std::uint64_t yz = (std::uint64_t(std::uint32_t(y)) << 32) | std::uint32_t(z);
        const std::uint64_t h = counterHash(seed, pits, std::uint64_t(x), yz);
        const Vec3d centre{double(x) + unitInterval(h), double(y) + unitInterval(mix64(h)),
                           double(z) + unitInterval(mix64(mix64(h)))};
        const double d2 = distanceSquared(q, centre);
        if (d2 < nearest) nearest = d2, pit = h;
      }
  return {nearest, pit};
}

// Pitting: granular disintegration hollows concave rock into pits, a seeded cellular (Worley F1)
// pattern: a pit in each cell of `spacing`, centred at a hashed point, the nearest pit's depth
// (1 − (r / radius)²)² (times its seeded 0.5..1) inward.
void addPitting(const SurfaceMesh& mesh, const DetailParams& params, std::vector<double>& offset) {
  const LookRelief& relief = params.processes.pitting;
  if (relief.amplitude <= 0 || relief.spacing <= 0) return;
  const double inv_spacing = 1.0 / relief.spacing;
  tbb::parallel_for(std::size_t(0), mesh.positions.size(), [&](std::size_t i) {
    if (onGroundCap(mesh, params, i)) return;
    const double weight = smoothstep(0.5, 0.2, exposure(mesh, i)) * uncovered(mesh, i);
    if (weight <= 0) return;
    const Vec3d q = scale(toVec3d(mesh.positions[i]), inv_spacing);
    if (!(std::abs(q[0]) < 1e9 && std::abs(q[1]) < 1e9 && std::abs(q[2]) < 1e9)) return;
    const auto [nearest, pit] = nearestPit(params.seed, q);
    const double x = nearest / (kPitRadius * kPitRadius);
    if (x >= 1.0) return;
    const double depth = kPitDepthMin + (1.0 - kPitDepthMin) * unitInterval(mix64(mix64(mix64(pit))));
    offset[i] -= relief.amplitude * weight * depth * (1.0 - x) * (1.0 - x);
  });
}

// Moves each vertex by offset[i] along its normal, and back where that would fold the surface (on
// a thin part or a tight crease): a triangle turned more than about 80 degrees from its
// undisplaced self, shrunk to a tenth of its area, or turned against an edge neighbour it faced
// with before. Then the offsets at its corners are halved and the triangles checked again; after
// kRounds, what still folds keeps no offset. Order-free, so the result does not depend on the
// thread count. Recomputes the normals.
void settleOffsets(SurfaceMesh& mesh, bool ground, std::vector<double>& offset) {
  const std::size_t n = mesh.positions.size();
  const std::vector<std::array<float, 3>> rest = mesh.positions;
  const std::size_t nt = mesh.triangles.size();
  const auto normals = [&](const std::vector<Vec3f>& at, std::vector<Vec3d>& out) {
    out.resize(nt);
    tbb::parallel_for(std::size_t(0), nt, [&](std::size_t f) {
      const auto& t = mesh.triangles[f];
      out[f] = triangleNormal(at[t[0]], at[t[1]], at[t[2]]);
    });
  };
  std::vector<Vec3d> before, after;
  normals(rest, before);
  const std::vector<std::array<std::uint32_t, 2>> pairs = facingPairs(mesh, before);

  const auto place = [&](std::size_t i) {
    auto& p = mesh.positions[i];
    const auto& nrm = mesh.normals[i];
    for (int a = 0; a < 3; ++a) p[a] = float(double(rest[i][a]) + offset[i] * nrm[a]);
    if (ground) p[2] = std::max(p[2], 0.0f);
  };
  constexpr int kRounds = 8;
  std::vector<char> fold(n);
  std::vector<char> bad(nt);
  for (int round = 0; round <= kRounds; ++round) {
    tbb::parallel_for(std::size_t(0), n, place);
    normals(mesh.positions, after);
    tbb::parallel_for(std::size_t(0), nt, [&](std::size_t f) {
      const double b2 = dot(before[f], before[f]), a2 = dot(after[f], after[f]);
      bad[f] = !(dot(before[f], after[f]) > 0.2 * std::sqrt(a2 * b2) && a2 > 0.01 * b2);
    });
    for (const auto& [f, g] : pairs)
      if (dot(after[f], after[g]) <= 0) bad[f] = bad[g] = 1;
    std::fill(fold.begin(), fold.end(), 0);
    bool any = false;
    for (std::size_t f = 0; f < nt; ++f)
      if (bad[f]) {
        for (std::uint32_t v : mesh.triangles[f]) fold[v] = 1;
        any = true;
      }
    if (!any || round == kRounds) break;
    for (std::size_t i = 0; i < n; ++i)
      if (fold[i]) offset[i] = round < kRounds - 1 ? 0.5 * offset[i] : 0.0;
  }
  computeVertexNormals(mesh);
}

}  // namespace

void displaceSurface(SurfaceMesh& mesh, const DetailParams& params) {
  const std::size_t n = mesh.positions.size();
  const bool processes = params.processes.any();
  if (n == 0 || (params.noise.amplitude <= 0.0 && !processes)) return;
  std::vector<double> offset(n, 0.0);  // along the normal, world units
  const bool noisy = addNoise(mesh, params, processes ? kNoiseUnderProcesses : 1.0, offset);
  if (!noisy && !processes) return;  // flat noise alone leaves the mesh as it is
  addLaminations(mesh, params, offset);
  addExfoliation(mesh, params, offset);
  addPitting(mesh, params, offset);
  settleOffsets(mesh, params.ground, offset);
}

}  // namespace rockbake
