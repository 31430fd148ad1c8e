#include "mesh/extract_surfaces.h"

#include "geometry/mesh_checks.h"
#include "geometry/triangle_geometry.h"

#include "mesh/subdivide.h"
#include "platform/openvdb_support.h"
#include "platform/side_by_side.h"
#include "platform/stopwatch.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

#include <spdlog/spdlog.h>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/TopologyToLevelSet.h>
#include <openvdb/tools/ValueTransformer.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rockbake {
namespace {

constexpr int kHalfWidth = 3;               // narrow band, voxels each side
constexpr int kPreviewHalfWidth = 2;        // enough for a width-1 Gaussian; the band's set-up costs 3 x this passes
constexpr int kMirrorLayers = 3;            // layers mirrored below the ground before smoothing
constexpr float kSideMargin = 0.05f;        // voxels: how far inside (outside) a sample of (not of) the material stays
constexpr float kThinMargin = 0.25f;        // voxels: the same for a sample smoothing moved across (a voxel-thin part)
constexpr double kOnFieldTolerance = 0.02;  // voxels: |phi| left after projectOntoField's steps that calls for a search
constexpr double kSearchReach = 2.0;        // voxels: how far along a direction that search looks

// Whether the voxel at index c is of `material`; on the ground, the mirrored
// layers below z = 0 follow their originals.
struct MaterialAt {
  const VoxelRock& rock;
  Material material;

  bool operator()(const openvdb::Coord& c) const {
    const GridLayout& g = rock.layout;
    const int z = c.z() < 0 && g.ground ? -1 - c.z() : c.z();
    return c.x() >= 0 && c.y() >= 0 && z >= 0 && c.x() < g.nx && c.y() < g.ny && z < g.nz &&
           (c.z() >= 0 || z < kMirrorLayers) && rock.material[g.index(c.x(), c.y(), z)] == material;
  }
};

// The material's voxels, active; null when there are none. On the ground, the
// lowest layers are mirrored below it, so smoothing sees walls that continue
// through z = 0 rather than a rounded foot.
openvdb::BoolGrid::Ptr occupancy(const VoxelRock& rock, Material material) {
  const GridLayout& g = rock.layout;
  auto mask = openvdb::BoolGrid::create(false);
  mask->setTransform(voxelCenterTransform(g));
  auto acc = mask->getAccessor();
  bool any = false;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] == material) {
          acc.setValueOn(openvdb::Coord(x, y, z), true);
          if (g.ground && z < kMirrorLayers) acc.setValueOn(openvdb::Coord(x, y, -1 - z), true);
          any = true;
        }
  return any ? mask : nullptr;
}

using Crossed = std::vector<std::pair<openvdb::Coord, bool>>;  // (sample, inside)

// The grid's voxels (with the mirrored layers below the ground) outside the
// band whose value is not at least `margin` on their side, in z, y, x order.
// Found among the material's voxels (those not inside) and among the field's
// inactive values under the margin (the interior's tiles: those not of the
// material), rather than by looking up every voxel of the grid.
std::vector<openvdb::Coord> droppedFromBand(const openvdb::FloatGrid& sdf, const MaterialAt& material_at,
                                            float margin) {
  const GridLayout& g = material_at.rock.layout;
  const int z0 = g.ground ? -kMirrorLayers : 0;
  std::vector<openvdb::Coord> dropped;
  auto acc = sdf.getConstAccessor();
  for (int z = z0; z < g.nz; ++z) {
    const int source = z < 0 ? -1 - z : z;  // a mirrored layer reads its original
    for (int y = 0; y < g.ny; ++y) {
      const Material* row = &material_at.rock.material[g.index(0, y, source)];
      for (int x = 0; x < g.nx; ++x) {
        if (row[x] != material_at.material) continue;
        const openvdb::Coord c(x, y, z);
        if (!acc.isValueOn(c) && acc.getValue(c) > -margin && material_at(c)) dropped.push_back(c);
      }
    }
  }
  const openvdb::CoordBBox grid(openvdb::Coord(0, 0, z0), openvdb::Coord(g.nx - 1, g.ny - 1, g.nz - 1));
  for (auto it = sdf.tree().cbeginValueOff(); it; ++it) {
    if (*it >= margin) continue;
    openvdb::CoordBBox box;
    it.getBoundingBox(box);
    box.intersect(grid);
    if (box.empty()) continue;
    for (auto c = box.begin(); c; ++c)
      if (!material_at(*c)) dropped.push_back(*c);
  }
  std::sort(dropped.begin(), dropped.end(), [](const openvdb::Coord& a, const openvdb::Coord& b) {
    return std::make_tuple(a.z(), a.y(), a.x()) < std::make_tuple(b.z(), b.y(), b.x());
  });
  return dropped;
}

// Smoothing must not change what the rock is: every sample keeps the side of
// its voxel (inside where the material is, outside elsewhere), so a one-voxel
// neck stays connected and a one-voxel gap stays open; the surface still moves
// freely between the samples. A sample smoothing moved across (a voxel-thin
// neck, fin or gap that it would erase) is held kThinMargin deep rather than
// kSideMargin: a feature a tenth of a voxel thick cannot be meshed without
// folding. Returns those samples.
Crossed holdSides(openvdb::FloatGrid& sdf, const MaterialAt& material_at) {
  const GridLayout& g = material_at.rock.layout;
  const float margin = kSideMargin * float(g.h), thin = kThinMargin * float(g.h);
  Crossed crossed;
  const auto keepSide = [&](const openvdb::Coord& c, float v, bool inside, auto&& set) {
    // Colluvium's voxel-thin parts (a lone voxel, a one-voxel veneer on a
    // face) are left to the smoothing: held, they stand as plates and slits.
    const bool moved_across = inside ? v > 0 : v < 0;
    if (moved_across && material_at.material != Material::Rock) return;
    if (inside && v > -margin) set(moved_across ? -thin : -margin);
    if (!inside && v < margin) set(moved_across ? thin : margin);
    if (moved_across) crossed.push_back({c, inside});
  };
  for (auto it = sdf.tree().beginValueOn(); it; ++it)
    keepSide(it.getCoord(), *it, material_at(it.getCoord()), [&](float v) { it.setValue(v); });
  // The filter's renormalisation can drop such a feature from the band
  // altogether (its voxels left as inactive background of the wrong sign).
  auto acc = sdf.getAccessor();
  for (const openvdb::Coord& c : droppedFromBand(sdf, material_at, margin))
    keepSide(c, acc.getValue(c), material_at(c), [&](float v) { acc.setValueOn(c, v); });
  return crossed;
}

// Held samples sit next to samples of the other side up to the band's width
// away: restore the distance bound |phi(a) - phi(b)| <= |a - b| around them,
// so the crossing lies about kThinMargin from the sample, not a sliver
// against it. Order-free (a min, or a max, over the held samples).
void restoreDistanceBound(openvdb::FloatGrid& sdf, const Crossed& crossed, const MaterialAt& material_at, int reach) {
  const double h = material_at.rock.layout.h;
  const float thin = kThinMargin * float(h);
  auto acc = sdf.getAccessor();
  for (const auto& [c, inside] : crossed)
    for (int dz = -reach; dz <= reach; ++dz)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const openvdb::Coord n = c.offsetBy(dx, dy, dz);
          if (material_at(n) == inside) continue;
          const float d = float(std::sqrt(double(dx * dx + dy * dy + dz * dz)) * h);
          const float v = acc.getValue(n);
          const float bound = inside ? -thin + d : thin - d;
          if (inside ? v > bound : v < bound) acc.setValueOn(n, bound);
        }
}

// `params.smoothing` passes of a width-1 Gaussian, every sample kept on its side.
double smoothKeepingSides(openvdb::FloatGrid& sdf, const MaterialAt& material_at, const ExtractParams& params) {
  const int passes = int(std::lround(std::clamp(params.smoothing, 0.0, 4.0)));
  if (passes == 0) return 0.0;
  openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(sdf);
  if (params.preview) filter.setSpatialScheme(openvdb::math::FIRST_BIAS);
  // A pass is OpenVDB's Gaussian, four box (mean) passes, each followed by a
  // renormalisation of the band: one sweep between the boxes (a box moves the
  // zero crossing by a fraction of a voxel, and one sweep keeps the band near
  // it a distance field), three after the last, so the field polygonised and
  // kept in rock.vdb is as well renormalised as after OpenVDB's own Gaussian,
  // at half the cost (docs/meshes.md). The preview sweeps once throughout.
  constexpr int kBoxes = 4, kBetweenSweeps = 1, kLastSweeps = 3;
  for (int box = 0; box < passes * kBoxes; ++box) {
    const bool last = box + 1 == passes * kBoxes;
    filter.setNormCount(params.preview || !last ? kBetweenSweeps : kLastSweeps);
    filter.mean(1);
  }
  Stopwatch clock;
  const Crossed crossed = holdSides(sdf, material_at);
  restoreDistanceBound(sdf, crossed, material_at, params.preview ? kPreviewHalfWidth : kHalfWidth);
  return clock.lap();
}

// Intersects the field with the half-space z >= 0: phi = max(phi, -z). Below
// the ground every sample turns outside; the two layers around z = 0 are
// written explicitly (interior tiles included) so the cap's crossings on
// vertical edges fall exactly on z = 0.
void clipAtGround(openvdb::FloatGrid& sdf, const GridLayout& g) {
  const float h = float(g.h);
  const auto below = [&](int k) { return -(float(g.origin[2]) + (float(k) + 0.5f) * h); };
  for (auto it = sdf.tree().beginValueOn(); it; ++it)
    if (it.getCoord().z() < -1) it.setValue(std::max(*it, below(it.getCoord().z())));
  auto acc = sdf.getAccessor();
  for (int k : {-1, 0})
    for (int y = -1; y <= g.ny; ++y)
      for (int x = -1; x <= g.nx; ++x) {
        const openvdb::Coord c(x, y, k);
        const float v = acc.getValue(c);
        const float clipped = std::max(v, below(k));
        if (clipped != v || acc.isValueOn(c)) acc.setValueOn(c, clipped);
      }
}

// The field's zero crossing as triangles and quads, facing outwards.
SurfaceMesh polygonise(const openvdb::FloatGrid& sdf, const GridLayout& g, const char* name) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(sdf, points, triangles, quads, 0.0, 0.0);
  SurfaceMesh mesh;
  mesh.name = name;
  mesh.positions.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    float z = points[i].z();
    // The cap's vertices sit on z = 0 up to rounding; make them exact.
    if (g.ground && z < 1e-4f * float(g.h)) z = 0.0f;
    mesh.positions[i] = {points[i].x(), points[i].y(), z};
  }
  mesh.triangles.reserve(triangles.size());
  for (const auto& t : triangles) mesh.triangles.push_back({t[0], t[1], t[2]});
  mesh.quads.reserve(quads.size());
  for (const auto& q : quads) mesh.quads.push_back({q[0], q[1], q[2], q[3]});
  // OpenVDB's winding is fixed for a level set; check it rather than rely on it.
  if (signedVolume(mesh) < 0) {
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    for (auto& q : mesh.quads) std::swap(q[1], q[3]);
  }
  return mesh;
}

SurfaceMesh extractMaterial(const VoxelRock& rock, Material material, const ExtractParams& params, const char* name,
                            openvdb::FloatGrid::Ptr* field) {
  Stopwatch clock;
  const openvdb::BoolGrid::Ptr mask = occupancy(rock, material);
  const double occupancy_seconds = clock.lap();
  if (!mask) {
    SurfaceMesh empty;
    empty.name = name;
    return empty;
  }
  // Zero crossing on the faces between occupied and empty voxels; no closing,
  // no dilation: the surface encloses exactly the voxels before smoothing.
  openvdb::FloatGrid::Ptr sdf =
      openvdb::tools::topologyToLevelSet(*mask, params.preview ? kPreviewHalfWidth : kHalfWidth, 0, 0, 0);
  const double level_set_seconds = clock.lap();
  const double hold_seconds = smoothKeepingSides(*sdf, MaterialAt{rock, material}, params);
  const double smooth_seconds = clock.lap() - hold_seconds;
  if (rock.layout.ground) clipAtGround(*sdf, rock.layout);
  if (field) *field = sdf;
  SurfaceMesh mesh = polygonise(*sdf, rock.layout, name);
  spdlog::debug(
      "{} extraction: occupancy {:.2f} s, level set {:.2f} s, smoothing {:.2f} s, sides held {:.2f} s, "
      "clip and polygonise {:.2f} s",
      name, occupancy_seconds, level_set_seconds, smooth_seconds, hold_seconds, clock.lap());
  return mesh;
}

}  // namespace

std::array<double, 3> footprintPivot(const VoxelRock& rock, double sink) {
  const GridLayout& g = rock.layout;
  int lo[3] = {g.nx, g.ny, g.nz}, hi[3] = {-1, -1, -1};
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const Material m = rock.material[g.index(x, y, z)];
        if (m != Material::Rock && m != Material::Colluvium) continue;
        const int c[3] = {x, y, z};
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a] + 1);
      }
  if (hi[0] < 0) lo[0] = lo[1] = lo[2] = 0, hi[0] = g.nx, hi[1] = g.ny, hi[2] = g.nz;
  const double h = g.h;
  return {g.origin[0] + 0.5 * (lo[0] + hi[0]) * h, g.origin[1] + 0.5 * (lo[1] + hi[1]) * h,
          (g.ground ? 0.0 : g.origin[2] + lo[2] * h) + sink};
}

double suggestedBurialDepth(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  if (!g.ground) return 0.0;
  std::vector<std::size_t> section(std::size_t(g.nz), 0);
  int top = -1;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] == Material::Rock) ++section[std::size_t(z)], top = z;
  if (top < 0) return 0.0;
  const int third = std::max(1, (top + 1) / 3);
  const std::size_t widest = *std::max_element(section.begin(), section.begin() + third);
  int z = 0;
  while (z < third && double(section[std::size_t(z)]) < 0.6 * double(widest)) ++z;
  return std::max(1, z) * g.h;
}

double sinkDepth(const VoxelRock& rock, double sink) {
  return sink < 0 ? suggestedBurialDepth(rock) : sink;
}

void movePivot(AssetMeshes& meshes, const std::array<double, 3>& pivot) {
  for (SurfaceMesh* m : {&meshes.rock, &meshes.colluvium})
    for (auto& p : m->positions)
      for (int a = 0; a < 3; ++a) p[a] = float(double(p[a]) - pivot[a]);
  for (int a = 0; a < 3; ++a)
    meshes.bounds_min[a] = float(double(meshes.bounds_min[a]) - pivot[a]),
    meshes.bounds_max[a] = float(double(meshes.bounds_max[a]) - pivot[a]);
}

namespace {

using Sampler = openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>;

// The zero crossing nearest to q (phi(q) = phi_q) on the segment q + t·dir,
// t in (0, reach], dir of unit length: marched in tenths of a voxel to the
// first change of sign, then bisected. False if the sign does not change.
bool crossingAlong(const Sampler& sample, const openvdb::Vec3d& q, double phi_q, const openvdb::Vec3d& dir,
                   double reach, double h, openvdb::Vec3d& crossing, double& distance) {
  const int steps = std::max(1, int(std::ceil(reach / (0.1 * h))));
  double lo = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double t = reach * k / steps;
    if (t >= distance) return false;  // a nearer crossing is known already
    if ((sample.wsSample(q + dir * t) > 0) == (phi_q > 0)) {
      lo = t;
      continue;
    }
    double hi = t;
    for (int i = 0; i < 24; ++i) {
      const double mid = 0.5 * (lo + hi);
      ((sample.wsSample(q + dir * mid) > 0) == (phi_q > 0) ? lo : hi) = mid;
    }
    // The side of the crossing where |phi| is smaller (they differ by bits).
    const double t_best = std::abs(sample.wsSample(q + dir * lo)) <= std::abs(sample.wsSample(q + dir * hi)) ? lo : hi;
    crossing = q + dir * t_best, distance = t_best;
    return true;
  }
  return false;
}

}  // namespace

void projectOntoField(SurfaceMesh& mesh, const SmoothedSdf* field_ptr, bool ground) {
  if (!field_ptr) return;
  const SmoothedSdf& field = *field_ptr;
  if (!field.grid || mesh.positions.empty()) return;
  const openvdb::FloatGrid& grid = *field.grid;
  const double h = grid.voxelSize()[0];
  const bool with_normals = mesh.normals.size() == mesh.positions.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 4096), [&](const auto& range) {
    // One accessor-backed sampler per task: samplers are not thread-safe. The
    // sampler keeps a reference to the accessor, so the accessor must outlive it.
    const openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
    const Sampler sample(accessor, grid.transform());
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      auto& p = mesh.positions[i];
      if (ground && p[2] == 0.0f) continue;
      openvdb::Vec3d q(p[0], p[1], p[2]);
      const auto gradient = [&](const openvdb::Vec3d& at) {
        openvdb::Vec3d g;
        for (int a = 0; a < 3; ++a) {
          openvdb::Vec3d d(0.0);
          d[a] = 0.5 * h;
          g[a] = (sample.wsSample(at + d) - sample.wsSample(at - d)) / h;
        }
        return g;
      };
      // Steps of at most half a voxel, until on the level set: Catmull-Clark
      // can pull a sharp corner or a thin leg more than a voxel inside.
      double phi = sample.wsSample(q);
      for (int step = 0; step < 6 && std::abs(phi) >= 1e-3 * h; ++step) {
        const openvdb::Vec3d g = gradient(q);
        const double g2 = g.lengthSqr();
        if (g2 < 1e-8) break;
        openvdb::Vec3d move = g * (phi / g2);
        if (move.length() > 0.5 * h) move *= 0.5 * h / move.length();  // never jump across a thin part
        q -= move;
        phi = sample.wsSample(q);
      }
      // Where the field is creased (a voxel-thin part, held by the side
      // margin), differences half a voxel wide straddle the crease and the
      // steps can bounce across it. Then take the nearest crossing found along
      // the gradient, the normal (both ways, two voxels) or the segment to a
      // nearby sample of the other sign (a crossing is certain on those),
      // bisected onto the field.
      if (std::abs(phi) > kOnFieldTolerance * h) {
        openvdb::Vec3d best = q;
        double distance = std::numeric_limits<double>::infinity();
        std::vector<openvdb::Vec3d> directions;
        const openvdb::Vec3d g = gradient(q);
        if (g.lengthSqr() > 1e-8) directions.push_back(g.unit());
        if (with_normals) {
          const openvdb::Vec3d n(mesh.normals[i][0], mesh.normals[i][1], mesh.normals[i][2]);
          if (n.lengthSqr() > 1e-12) directions.push_back(n.unit());
        }
        for (const openvdb::Vec3d& d : directions)
          for (double s : {-1.0, 1.0}) crossingAlong(sample, q, phi, d * s, kSearchReach * h, h, best, distance);
        const openvdb::Vec3d index = grid.worldToIndex(q);
        const openvdb::Coord base(int(std::floor(index[0])), int(std::floor(index[1])), int(std::floor(index[2])));
        for (int dz = -1; dz <= 2; ++dz)
          for (int dy = -1; dy <= 2; ++dy)
            for (int dx = -1; dx <= 2; ++dx) {
              const openvdb::Coord c = base.offsetBy(dx, dy, dz);
              if ((accessor.getValue(c) > 0) == (phi > 0)) continue;
              const openvdb::Vec3d to = grid.indexToWorld(c) - q;
              const double length = to.length();
              if (length > 0) crossingAlong(sample, q, phi, to / length, length, h, best, distance);
            }
        q = best;
      }
      p = {float(q[0]), float(q[1]), ground ? std::max(float(q[2]), 0.0f) : float(q[2])};
    }
  });
  computeVertexNormals(mesh);
}

double matchVolume(SurfaceMesh& mesh, double target_volume, double max_offset, bool ground) {
  if (mesh.triangles.empty() || mesh.normals.size() != mesh.positions.size()) return 0.0;
  double total = 0.0;
  // Two steps of delta = (target - V) / area: the second absorbs the change of area.
  for (int step = 0; step < 2; ++step) {
    double area = 0.0;
    for (const auto& t : mesh.triangles) {
      const auto& a = mesh.positions[t[0]];
      const auto& b = mesh.positions[t[1]];
      const auto& c = mesh.positions[t[2]];
      const bool cap = ground && a[2] == 0.0f && b[2] == 0.0f && c[2] == 0.0f;
      if (!cap) area += triangleArea(a, b, c);
    }
    if (area <= 0) break;
    const double delta =
        std::clamp((target_volume - signedVolume(mesh)) / area, -max_offset - total, max_offset - total);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      auto& p = mesh.positions[i];
      if (ground && p[2] == 0.0f) continue;
      for (int a = 0; a < 3; ++a) p[a] = float(double(p[a]) + delta * mesh.normals[i][a]);
      if (ground) p[2] = std::max(p[2], 0.0f);
    }
    total += delta;
    computeVertexNormals(mesh);
  }
  return total;
}

std::shared_ptr<const SmoothedSdf> offsetField(const std::shared_ptr<const SmoothedSdf>& field, double delta,
                                               bool ground) {
  if (!field || !field->grid || delta == 0.0) return field;
  openvdb::FloatGrid::Ptr moved = field->grid->deepCopy();
  const float d = float(delta);
  const openvdb::math::Transform& xform = moved->transform();
  // The ground clip -z stays where it is (max(phi - d, -z)): only the rock's own
  // surface moved, the cap did not. It was written at index z <= 0 only.
  const auto clipAt = [&](int k) { return -float(xform.indexToWorld(openvdb::Coord(0, 0, k)).z()); };
  openvdb::tools::foreach (moved->beginValueAll(), [&](const openvdb::FloatGrid::ValueAllIter& it) {
    float v = *it - d;
    if (ground) {
      openvdb::CoordBBox box;
      it.getBoundingBox(box);
      if (box.min().z() <= 0) v = std::max(v, clipAt(std::min(box.max().z(), 0)));
    }
    it.setValue(v);
  });
  return std::make_shared<const SmoothedSdf>(SmoothedSdf{moved});
}

AssetMeshes extractSurfaces(const VoxelRock& rock, const ExtractParams& params,
                            std::shared_ptr<const SmoothedSdf>* rock_sdf) {
  initializeOpenVdb();
  AssetMeshes out;
  openvdb::FloatGrid::Ptr rock_field;
  try {
    sideBySide(
        [&] { out.rock = extractMaterial(rock, Material::Rock, params, "rock", rock_sdf ? &rock_field : nullptr); },
        [&] { out.colluvium = extractMaterial(rock, Material::Colluvium, params, "colluvium", nullptr); });
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error(std::string("mesh extraction failed: ") + e.what());
  }
  updateBounds(out);
  if (rock_sdf) *rock_sdf = rock_field ? std::make_shared<const SmoothedSdf>(SmoothedSdf{rock_field}) : nullptr;
  return out;
}

}  // namespace rockbake
