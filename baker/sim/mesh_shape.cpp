#include "sim/mesh_shape.h"

#include "platform/openvdb_support.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/parallel_for.h>

namespace rockbake {

std::vector<std::uint8_t> voxelizeMesh(const TriangleMesh& mesh, const GridLayout& g) {
  initializeOpenVdb();

  // Index (i, j, k) of the level set is voxel (i, j, k) of the grid: its centre.
  const auto transform = voxelCenterTransform(g);
  std::vector<openvdb::Vec3s> points;
  points.reserve(mesh.positions.size());
  for (const auto& p : mesh.positions) points.push_back(transform->worldToIndex(openvdb::Vec3d(p[0], p[1], p[2])));
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  // Points are already in index space, so the level set is built with a unit transform.
  const auto index_space = openvdb::math::Transform::createLinearTransform(1.0);
  const openvdb::FloatGrid::Ptr sdf =
      openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*index_space, points, triangles, 2.0f);

  std::vector<std::uint8_t> inside(g.cellCount(), 0);
  tbb::parallel_for(0, g.nz, [&](int z) {
    auto accessor = sdf->getConstAccessor();
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        inside[g.index(x, y, z)] = accessor.getValue(openvdb::Coord(x, y, z)) < 0.f ? 1 : 0;
  });
  return inside;
}

}  // namespace rockbake
