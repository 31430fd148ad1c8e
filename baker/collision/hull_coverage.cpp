#include "collision/hull_coverage.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "collision/point_hull.h"

namespace rockbake {
namespace {
std::vector<HullPlane> facePlanes(const ConvexHull& hull) {
  std::vector<HullPlane> planes;
  for (const auto& t : hull.triangles) {
    const Vec3d& a = hull.positions[t[0]];
    const Vec3d n = cross(sub(hull.positions[t[1]], a), sub(hull.positions[t[2]], a));
    const double len = length(n);
    if (len == 0.0) continue;
    planes.push_back({scale(n, 1.0 / len), dot(n, a) / len});
  }
  return planes;
}

}  // namespace

HullCoverage measureCoverage(const VoxelRock& rock, Material material, const std::vector<ConvexHull>& hulls) {
  const GridLayout& g = rock.layout;
  std::vector<unsigned char> inside(g.cellCount(), 0);
  const double eps = 1e-6 * g.h;
  for (const ConvexHull& hull : hulls) {
    const std::vector<HullPlane> planes = facePlanes(hull);
    int lo[3] = {g.nx, g.ny, g.nz}, hi[3] = {-1, -1, -1};
    for (const Vec3d& p : hull.positions)
      for (int a = 0; a < 3; ++a) {
        const double c = (p[a] - g.origin[a]) / g.h - 0.5;  // in voxel centres
        lo[a] = std::min(lo[a], int(std::floor(c)));
        hi[a] = std::max(hi[a], int(std::ceil(c)));
      }
    lo[0] = std::max(lo[0], 0), lo[1] = std::max(lo[1], 0), lo[2] = std::max(lo[2], 0);
    hi[0] = std::min(hi[0], g.nx - 1), hi[1] = std::min(hi[1], g.ny - 1), hi[2] = std::min(hi[2], g.nz - 1);
    tbb::parallel_for(lo[2], hi[2] + 1, [&](int z) {
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const Vec3d c = g.center(x, y, z);
          if (std::all_of(planes.begin(), planes.end(),
                          [&](const HullPlane& p) { return dot(p.normal, c) <= p.offset + eps; }))
            inside[g.index(x, y, z)] = 1;
        }
    });
  }
  HullCoverage coverage;
  for (std::size_t i = 0; i < inside.size(); ++i) {
    if (rock.material[i] == material) {
      ++coverage.voxels;
      coverage.voxels_inside += inside[i];
    } else if (rock.material[i] == Material::Air) {
      coverage.air_inside += inside[i];
    }
  }
  return coverage;
}

}  // namespace rockbake
