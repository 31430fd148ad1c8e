#include "mesh/surface_detail.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/hash.h"
#include "mesh/subdivide.h"
#include "sim/durability.h"

namespace rockbake {

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
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    auto& p = mesh.positions[i];
    if (params.ground && p[2] == 0.0f) return;  // the ground cap stays flat on the ground
    const double softness =
        range > 0 ? std::clamp((double(params.durability_max) - mesh.durability[i]) / range, 0.0, 1.0) : 0.5;
    const double exposure = std::clamp(double(mesh.curvature[i]), 0.0, 1.0);
    const double covered = std::clamp(double(mesh.colluvium[i]), 0.0, 1.0);
    const double d = scale * value[i] * (0.5 + softness) * (0.5 + exposure) * (1.0 - covered);
    const auto& nrm = mesh.normals[i];
    for (int a = 0; a < 3; ++a) p[a] = float(double(p[a]) + d * nrm[a]);
    if (params.ground) p[2] = std::max(p[2], 0.0f);
  });
  computeVertexNormals(mesh);
}

}  // namespace rockbake
