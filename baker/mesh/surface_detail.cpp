#include "mesh/surface_detail.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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

}  // namespace

void displaceSurface(SurfaceMesh& mesh, const DetailParams& params) {
  const std::size_t n = mesh.positions.size();
  if (n == 0 || params.noise.amplitude <= 0.0) return;
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
  if (rms <= 0) return;

  const double range = double(params.durability_max) - params.durability_min;
  const double scale = params.noise.amplitude / rms;
  std::vector<double> offset(n, 0.0);  // along the normal, world units
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    if (params.ground && mesh.positions[i][2] == 0.0f) return;  // the ground cap stays flat on the ground
    const double softness =
        range > 0 ? std::clamp((double(params.durability_max) - mesh.durability[i]) / range, 0.0, 1.0) : 0.5;
    const double exposure = std::clamp(double(mesh.curvature[i]), 0.0, 1.0);
    const double covered = std::clamp(double(mesh.colluvium[i]), 0.0, 1.0);
    offset[i] = scale * value[i] * (0.5 + softness) * (0.5 + exposure) * (1.0 - covered);
  });

  // Where the offsets would fold the surface (on a thin part or a tight
  // crease): a triangle turned more than about 80 degrees from its undisplaced
  // self, shrunk to a tenth of its area, or turned against an edge neighbour
  // it faced with before. Then the offsets at its corners are halved and the
  // triangles checked again; after kRounds, what still folds keeps no offset.
  // Order-free, so the result does not depend on the thread count.
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
    if (params.ground) p[2] = std::max(p[2], 0.0f);
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

}  // namespace rockbake
