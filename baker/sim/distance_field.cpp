#include "sim/distance_field.h"

#include <algorithm>
#include <cmath>

#include <openvdb/openvdb.h>
#include <openvdb/tools/FastSweeping.h>
#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/ValueTransformer.h>
#include <tbb/parallel_for.h>

#include "core/openvdb_support.h"

namespace rockbake {

std::vector<float> signedDistance(const std::vector<std::uint8_t>& inside, const GridLayout& g, double reach) {
  initializeOpenVdb();
  const auto occupied = [&](int x, int y, int z) -> float {
    if (x < 0 || y < 0 || x >= g.nx || y >= g.ny || z >= g.nz) return 0.f;
    if (z < 0) return g.ground && inside[g.index(x, y, 0)] ? 1.f : 0.f;
    return inside[g.index(x, y, z)] ? 1.f : 0.f;
  };

  // The cells next to the boundary, layer by layer (so their order does not depend on the threads).
  std::vector<std::vector<openvdb::Coord>> boundary(std::size_t(g.nz));
  tbb::parallel_for(0, g.nz, [&](int z) {
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const float here = occupied(x, y, z);
        for (const auto& o : kFaceNeighbours)
          if (occupied(x + o[0], y + o[1], z + o[2]) != here) {
            boundary[std::size_t(z)].emplace_back(x, y, z);
            break;
          }
      }
  });

  // Occupancy as a fog (1 inside, 0 outside) over a band around the boundary:
  // fast sweeping solves |∇d| = 1 from the iso-surface ½ outwards, in index units.
  openvdb::FloatGrid::Ptr fog = openvdb::FloatGrid::create(0.f);
  {
    auto accessor = fog->getAccessor();
    for (const auto& layer : boundary)
      for (const auto& c : layer) accessor.setValueOn(c, 1.f);
  }
  const int band = int(std::ceil(reach / g.h)) + 1;
  openvdb::tools::dilateActiveValues(fog->tree(), band, openvdb::tools::NN_FACE_EDGE_VERTEX,
                                     openvdb::tools::IGNORE_TILES);
  openvdb::tools::foreach (fog->beginValueOn(), [&](const openvdb::FloatGrid::ValueOnIter& it) {
    const openvdb::Coord c = it.getCoord();
    it.setValue(occupied(c.x(), c.y(), c.z()));
  });
  const openvdb::FloatGrid::Ptr sdf = openvdb::tools::fogToSdf(*fog, 0.5f, 1);

  const float far = float(reach);
  std::vector<float> distance(g.cellCount());
  tbb::parallel_for(0, g.nz, [&](int z) {
    auto accessor = sdf->getConstAccessor();
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const std::size_t i = g.index(x, y, z);
        float d = 0.f;
        const bool in_band = accessor.probeValue(openvdb::Coord(x, y, z), d) && std::isfinite(d);
        distance[i] = in_band ? std::clamp(float(d * g.h), -far, far) : (inside[i] ? -far : far);
      }
  });
  return distance;
}

}  // namespace rockbake
