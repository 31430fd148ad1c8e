#include "sim/shapes.h"

#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "core/hash.h"
#include "sim/distance_field.h"
#include "sim/durability.h"
#include "sim/family.h"
#include "sim/grid_layout.h"
#include "sim/mesh_shape.h"

namespace rockbake {
namespace {

// Lets a boundary that falls exactly on a voxel centre count as inside.
constexpr double kEps = 1e-9;

using InsideTest = std::function<bool(double x, double y, double z)>;

// Inside tests in world coordinates; (cx, cy) is the centre, bz the base.
InsideTest insideTest(const ResolvedShape& shape, double cx, double cy, double bz, const SimParams& preset) {
  struct Visitor {
    double cx, cy, bz;
    const ResolvedShape& shape;
    const SimParams& preset;

    InsideTest operator()(const BoxShape& b) const {
      const Vec3d s = b.size;
      return [=, cx = cx, cy = cy, bz = bz](double x, double y, double z) {
        return std::abs(x - cx) <= s[0] / 2 + kEps && std::abs(y - cy) <= s[1] / 2 + kEps && z >= bz - kEps &&
               z <= bz + s[2] + kEps;
      };
    }
    InsideTest operator()(const CylinderShape& c) const {
      return [=, cx = cx, cy = cy, bz = bz](double x, double y, double z) {
        return std::hypot(x - cx, y - cy) <= c.radius + kEps && z >= bz - kEps && z <= bz + c.height + kEps;
      };
    }
    InsideTest operator()(const SphereShape& s) const {
      const double cz = bz + s.radius;
      return [=, cx = cx, cy = cy, bz = bz](double x, double y, double z) {
        return std::hypot(x - cx, y - cy, z - cz) <= s.radius + kEps;
      };
    }
    InsideTest operator()(const InsideCornerShape& c) const {
      const double x0 = cx - c.size[0] / 2, y0 = cy - c.size[1] / 2;
      return [=, cx = cx, cy = cy, bz = bz](double x, double y, double z) {
        const double u = x - x0, v = y - y0;
        if (z < bz - kEps || z > bz + c.size[2] + kEps) return false;
        if (u < -kEps || v < -kEps || u > c.size[0] + kEps || v > c.size[1] + kEps) return false;
        return u <= c.wall + kEps || v <= c.wall + kEps;  // the two walls of the L
      };
    }
    InsideTest operator()(const ImageShape& img) const {
      const GrayImage& image = shape.image;
      const auto white = [&image](int px, int py) {
        return px >= 0 && py >= 0 && px < image.width && py < image.height && image.at(px, py) >= 128;
      };
      const double W = image.width, H = image.height;
      if (img.mode == ImageMode::Extrude) {
        // The footprint fills the domain's x-y extent as far as its aspect allows.
        const double pixel = std::min(preset.grid.size[0] / W, preset.grid.size[1] / H);
        return [=, cx = cx, cy = cy, bz = bz](double x, double y, double z) {
          if (z < bz - kEps || z > bz + img.height + kEps) return false;
          const int px = int(std::floor((x - cx) / pixel + W / 2));
          const int py = int(std::floor(H / 2 - (y - cy) / pixel));  // image rows run down, y runs up
          return white(px, py);
        };
      }
      // Revolve: the profile's rows span `height`; its left edge is the axis.
      const double pixel = img.height / H;
      return [=, cx = cx, cy = cy, bz = bz](double x, double y, double z) {
        if (z < bz - kEps) return false;
        const int px = int(std::floor(std::hypot(x - cx, y - cy) / pixel));
        const int py = int(std::floor(H - (z - bz) / pixel));
        return white(px, py);
      };
    }
    InsideTest operator()(const MeshShape&) const { return {}; }  // voxelized as a whole, below
  };
  return std::visit(Visitor{cx, cy, bz, shape, preset}, shape.params.kind);
}

// The blockout (world units) with its bounding box centred on (cx, cy) and
// resting at z = bz.
TriangleMesh placeMesh(TriangleMesh mesh, const Vec3d& center) {
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (auto& p : mesh.positions)
    for (int a = 0; a < 3; ++a) {
      lo[std::size_t(a)] = std::min(lo[std::size_t(a)], p[std::size_t(a)]);
      hi[std::size_t(a)] = std::max(hi[std::size_t(a)], p[std::size_t(a)]);
    }
  const Vec3d shift{center[0] - 0.5 * (lo[0] + hi[0]), center[1] - 0.5 * (lo[1] + hi[1]), center[2] - lo[2]};
  for (auto& p : mesh.positions)
    for (int a = 0; a < 3; ++a) p[std::size_t(a)] += shift[std::size_t(a)];
  return mesh;
}

// docs/model.md §8 variation: the boundary moved along its normal by seeded noise, up
// to `amplitude` out (noise > 0) or in: rock where the signed distance to the
// shape is below the displacement.
void varyBoundary(std::vector<std::uint8_t>& inside, const GridLayout& g, const ShapeVariation& v, std::uint64_t seed) {
  const SignedDistanceField distance = signedDistance(inside, g, variationReach(v, g.h));
  const PerlinNoise noise(counterHash(seed, purposeId("shape-variation"), 0, 0));
  // Off the lattice, where Perlin noise is 0 for every seed.
  Vec3d offset;
  for (std::size_t a = 0; a < 3; ++a)
    offset[a] = 64.0 * unitInterval(counterHash(seed, purposeId("shape-variation-offset"), 0, a));
  tbb::parallel_for(0, g.nz, [&](int z) {
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const std::size_t i = g.index(x, y, z);
        if (std::abs(distance[i]) > v.amplitude + g.h) continue;  // beyond the noise's reach
        const Vec3d p = g.center(x, y, z);
        const double n = noise.fractal(p[0] / v.period + offset[0], p[1] / v.period + offset[1],
                                       p[2] / v.period + offset[2], v.octaves);
        inside[i] = distance[i] < v.amplitude * n ? 1 : 0;
      }
  });
}

// The blockout's inside test in the blockout's own frame (the preset's
// grid.size, the shape at its centre): an analytic test, or a blockout mesh
// voxelized on the preset's own grid and read at the nearest voxel.
InsideTest blockoutInside(const ResolvedShape& shape, const SimParams& preset, const Vec3d& center) {
  if (!std::holds_alternative<MeshShape>(shape.params.kind))
    return insideTest(shape, center[0], center[1], center[2], preset);
  SimParams own = preset;
  own.family.reset();
  const GridLayout g = computeGridLayout(own);
  auto flags = std::make_shared<std::vector<std::uint8_t>>(voxelizeMesh(placeMesh(shape.mesh, center), g));
  return [g, flags](double x, double y, double z) {
    const int i = int(std::floor((x - g.origin[0]) / g.h)), j = int(std::floor((y - g.origin[1]) / g.h)),
              k = int(std::floor((z - g.origin[2]) / g.h));
    return g.contains(i, j, k) && (*flags)[g.index(i, j, k)] != 0;
  };
}

// docs/model.md §12 fracture: each cut takes away the part of the rock beyond a
// plane of its joint set, `depth` of the rock's width along the plane's normal.
void cutAlongJoints(std::vector<std::uint8_t>& inside, const GridLayout& g, const Individual& individual) {
  for (const Individual::Cut& cut : individual.cuts) {
    // The rock's extent along the normal, layer by layer (min and max do not depend on the order).
    std::vector<double> layer_lo(std::size_t(g.nz), 1e300), layer_hi(std::size_t(g.nz), -1e300);
    tbb::parallel_for(0, g.nz, [&](int z) {
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x)
          if (inside[g.index(x, y, z)]) {
            const double d = dot(g.center(x, y, z), cut.normal);
            layer_lo[std::size_t(z)] = std::min(layer_lo[std::size_t(z)], d);
            layer_hi[std::size_t(z)] = std::max(layer_hi[std::size_t(z)], d);
          }
    });
    const double lo = *std::min_element(layer_lo.begin(), layer_lo.end());
    const double hi = *std::max_element(layer_hi.begin(), layer_hi.end());
    if (lo > hi) return;
    const double plane = hi - cut.depth * (hi - lo);
    tbb::parallel_for(0, g.nz, [&](int z) {
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x)
          if (inside[g.index(x, y, z)] && dot(g.center(x, y, z), cut.normal) > plane) inside[g.index(x, y, z)] = 0;
    });
  }
}

// Which voxel centres the individual holds, before the domain clips it.
std::vector<std::uint8_t> individualInside(const ResolvedShape& shape, const SimParams& preset, const GridLayout& g,
                                           const Individual& individual) {
  const Vec3d center = blockoutBaseCenter(preset);
  if (!individual.drawn && std::holds_alternative<MeshShape>(shape.params.kind))
    return voxelizeMesh(placeMesh(shape.mesh, center), g);
  const InsideTest inside = blockoutInside(shape, preset, center);
  std::vector<std::uint8_t> flags(g.cellCount(), 0);
  // A family's individual lies within its box (sim/family.h): the apron's room around it holds no rock.
  const auto inBox = [&](const Vec3d& p) {
    if (!individual.drawn) return true;
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] < individual.box_lo[a] || p[a] > individual.box_hi[a]) return false;
    return true;
  };
  tbb::parallel_for(0, g.nz, [&](int z) {
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const Vec3d world = g.center(x, y, z);
        if (!inBox(world)) continue;
        const Vec3d p = toBlockout(individual, preset, world);
        flags[g.index(x, y, z)] = inside(p[0], p[1], p[2]) ? 1 : 0;
      }
  });
  cutAlongJoints(flags, g, individual);
  return flags;
}

}  // namespace

VoxelRock buildInitialRock(const ResolvedShape& shape, const SimParams& preset, std::string* warning) {
  VoxelRock rock;
  rock.layout = computeGridLayout(preset);
  const GridLayout& g = rock.layout;
  requireSimulationCells(g);
  const Individual individual = drawIndividual(preset);
  const Vec3d& domain = individual.domain;
  rock.material.assign(g.cellCount(), Material::Air);
  std::vector<std::uint8_t> flags = individualInside(shape, preset, g, individual);
  if (const auto& variation = preset.shape.variation; variation && variation->amplitude > 0)
    varyBoundary(flags, g, *variation, preset.seed);

  std::vector<char> clipped(std::size_t(g.nz), 0);
  tbb::parallel_for(0, g.nz, [&](int z) {
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const Vec3d p = g.center(x, y, z);
        if (!flags[g.index(x, y, z)]) continue;
        const bool in_domain = p[0] > 0 && p[1] > 0 && p[0] < domain[0] && p[1] < domain[1] && p[2] < domain[2];
        if (in_domain)
          rock.material[g.index(x, y, z)] = Material::Rock;
        else
          clipped[std::size_t(z)] = 1;
      }
  });
  if (std::find(clipped.begin(), clipped.end(), 1) != clipped.end()) {
    const char* clip = "the shape reaches beyond grid.size and was clipped to it";
    if (warning)
      *warning = clip;
    else
      spdlog::warn("{}", clip);
  }

  resetRockValues(rock);
  if (preset.durability.rind) rock.rind = rindCoverage(rock, preset.durability.rind->depth);
  assignDurability(rock, DurabilityField(preset.durability.graph, preset.seed, 0),
                   Geology(individualDurability(preset), domain, preset.seed));
  return rock;
}

}  // namespace rockbake
