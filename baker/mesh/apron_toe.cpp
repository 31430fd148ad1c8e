#include "mesh/apron_toe.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/disjoint_set.h"
#include "mesh/ground_contact.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

// Per vertex: whether its piece of the surface touches the ground cap.
std::vector<std::uint8_t> onGroundPieces(const SurfaceMesh& m, double eps) {
  DisjointSet pieces(m.positions.size());
  for (const auto& t : m.triangles) pieces.unite(t[0], t[1]), pieces.unite(t[1], t[2]);
  std::vector<std::uint8_t> grounded_root(m.positions.size(), 0), grounded(m.positions.size(), 0);
  for (std::size_t v = 0; v < m.positions.size(); ++v)
    if (double(m.positions[v][2]) <= eps) grounded_root[pieces.find(std::uint32_t(v))] = 1;
  for (std::size_t v = 0; v < m.positions.size(); ++v) grounded[v] = grounded_root[pieces.find(std::uint32_t(v))];
  return grounded;
}

double cot(double degrees) {
  return 1.0 / std::tan(degrees * std::numbers::pi / 180.0);
}

}  // namespace

void shapeApronToe(AssetMeshes& meshes, const GridLayout& g, const ApronToeParams& params) {
  SurfaceMesh& c = meshes.colluvium;
  if (!g.ground || c.triangles.empty() || params.angle <= 0 || params.angle >= kRimSlope) return;
  const double h = g.h, eps = 1e-4 * h, band = params.height * h;
  const std::array<double, 2> lo{std::min(double(meshes.bounds_min[0]), g.origin[0]),
                                 std::min(double(meshes.bounds_min[1]), g.origin[1])};
  const std::array<double, 2> hi{std::max(double(meshes.bounds_max[0]), g.origin[0] + g.nx * h),
                                 std::max(double(meshes.bounds_max[1]), g.origin[1] + g.ny * h)};
  const PlaneDistance rim(groundContactPoints(meshes, 0.0, eps, 0.75 * h, 0.5 * h), lo, hi, 0.5 * h);
  const PlaneDistance rock(groundCapRim(meshes.rock, 0.0, eps, 0.5 * h), lo, hi, 0.5 * h);
  if (rim.empty() || rock.empty()) return;
  const double spread = band * (cot(params.angle) - cot(kRimSlope));  // at the rim
  const std::vector<std::uint8_t> grounded = onGroundPieces(c, eps);
  bool moved = false;
  for (std::size_t v = 0; v < c.positions.size(); ++v) {
    auto& p = c.positions[v];
    const double z = p[2];
    if (!grounded[v] || z >= band) continue;
    // The rim moves out by `spread`, the band less with height, and inwards of the rim half a
    // distance less per distance: the shift falls by half of what a vertex lies further in, so
    // nothing overtakes what lies beyond it and nothing folds.
    const double e = rim.at(p[0], p[1]);
    const double shift = spread * (1.0 - std::max(0.0, z) / band) - 0.5 * e;
    if (shift <= 0) continue;
    const std::array<double, 2> out = rock.gradient(p[0], p[1]);
    const double norm = std::hypot(out[0], out[1]);
    if (norm < 1e-6) continue;
    p[0] = float(p[0] + shift * out[0] / norm);
    p[1] = float(p[1] + shift * out[1] / norm);
    moved = true;
  }
  if (moved) computeVertexNormals(c);
}

}  // namespace rockbake
