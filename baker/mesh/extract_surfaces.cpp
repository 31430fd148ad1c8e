#include "mesh/extract_surfaces.h"

#include "core/mesh_checks.h"

#include "core/openvdb_support.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/TopologyToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/parallel_invoke.h>

namespace rockbake {
namespace {

constexpr int kHalfWidth = 3;     // narrow band, voxels each side
constexpr int kMirrorLayers = 3;  // layers mirrored below the ground before smoothing

SurfaceMesh extractMaterial(const VoxelRock& rock, Material material, const ExtractParams& params, const char* name,
                            openvdb::FloatGrid::Ptr* field) {
  const GridLayout& g = rock.layout;
  SurfaceMesh mesh;
  mesh.name = name;

  auto mask = openvdb::BoolGrid::create(false);
  mask->setTransform(voxelCenterTransform(g));
  {
    auto acc = mask->getAccessor();
    bool any = false;
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x)
          if (rock.material[g.index(x, y, z)] == material) {
            acc.setValueOn(openvdb::Coord(x, y, z), true);
            // On the ground, mirror the lowest layers below it, so smoothing
            // sees walls that continue through z = 0 rather than a rounded foot.
            if (g.ground && z < kMirrorLayers) acc.setValueOn(openvdb::Coord(x, y, -1 - z), true);
            any = true;
          }
    if (!any) return mesh;
  }

  // Zero crossing on the faces between occupied and empty voxels; no closing,
  // no dilation: the surface encloses exactly the voxels before smoothing.
  openvdb::FloatGrid::Ptr sdf = openvdb::tools::topologyToLevelSet(*mask, kHalfWidth, 0, 0, 0);
  const int passes = int(std::lround(std::clamp(params.smoothing, 0.0, 4.0)));
  if (passes > 0) {
    openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*sdf);
    for (int i = 0; i < passes; ++i) filter.gaussian(1);
  }
  if (g.ground) {
    // Intersect with the half-space z >= 0: phi = max(phi, -z). Below the
    // ground every sample turns outside; the two layers around z = 0 are
    // written explicitly (interior tiles included) so the cap's crossings on
    // vertical edges fall exactly on z = 0.
    const float h = float(g.h);
    const auto below = [&](int k) { return -(float(g.origin[2]) + (float(k) + 0.5f) * h); };
    for (auto it = sdf->tree().beginValueOn(); it; ++it)
      if (it.getCoord().z() < -1) it.setValue(std::max(*it, below(it.getCoord().z())));
    auto acc = sdf->getAccessor();
    for (int k : {-1, 0})
      for (int y = -1; y <= g.ny; ++y)
        for (int x = -1; x <= g.nx; ++x) {
          const openvdb::Coord c(x, y, k);
          const float v = acc.getValue(c);
          const float clipped = std::max(v, below(k));
          if (clipped != v || acc.isValueOn(c)) acc.setValueOn(c, clipped);
        }
  }

  if (field) *field = sdf;

  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*sdf, points, triangles, quads, 0.0, 0.0);

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

}  // namespace

AssetMeshes extractSurfaces(const VoxelRock& rock, const ExtractParams& params,
                            std::shared_ptr<const SmoothedSdf>* rock_sdf) {
  initializeOpenVdb();
  AssetMeshes out;
  openvdb::FloatGrid::Ptr rock_field;
  try {
    tbb::parallel_invoke(
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
