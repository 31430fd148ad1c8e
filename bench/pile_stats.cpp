// The colluvium piles of baked assets, measured from their rock.vdb
// (BoolGrid `colluvium`, index space = the simulation's voxels, z = 0 on the
// ground): how many voxels; how far they spread (footprint: the (x, y)
// columns holding any, and that area in world units); how thick they lie
// (colluvium voxels per column: the largest, the 90th percentile and the
// mean); and how high the highest colluvium voxel's top stands above the
// ground. One line per file; bench/README.md compares builds with it.
//   rockbake_pile_stats ROCK.vdb...
#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

#include <openvdb/openvdb.h>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: rockbake_pile_stats ROCK.vdb...\n");
    return 2;
  }
  openvdb::initialize();
  std::printf("%-44s %8s %8s %9s %6s %6s %6s %6s\n", "file", "voxels", "columns", "area", "thick", "p90", "mean",
              "top");
  for (int i = 1; i < argc; ++i) {
    openvdb::io::File file(argv[i]);
    file.open();
    if (!file.hasGrid("colluvium")) {
      std::fprintf(stderr, "%s: no colluvium grid\n", argv[i]);
      return 1;
    }
    const auto grid = openvdb::gridPtrCast<openvdb::BoolGrid>(file.readGrid("colluvium"));
    const double h = grid->voxelSize()[0];
    std::map<std::pair<int, int>, int> thickness;  // colluvium voxels per (x, y) column
    std::size_t voxels = 0;
    int top = 0;
    for (auto it = grid->tree().cbeginValueOn(); it; ++it) {
      if (!*it) continue;
      const openvdb::CoordBBox box = it.getBoundingBox();  // one voxel, or a whole tile of them
      for (int x = box.min().x(); x <= box.max().x(); ++x)
        for (int y = box.min().y(); y <= box.max().y(); ++y) thickness[{x, y}] += box.dim().z();
      voxels += std::size_t(box.volume());
      top = std::max(top, box.max().z() + 1);
    }
    std::vector<int> columns;
    for (const auto& [column, t] : thickness) columns.push_back(t);
    std::sort(columns.begin(), columns.end());
    const int thickest = columns.empty() ? 0 : columns.back();
    const int p90 = columns.empty() ? 0 : columns[std::size_t(0.9 * double(columns.size() - 1))];
    const double mean = columns.empty() ? 0.0 : double(voxels) / double(columns.size());
    std::printf("%-44s %8zu %8zu %9.3f %6d %6d %6.2f %6d\n", argv[i], voxels, columns.size(),
                double(columns.size()) * h * h, thickest, p90, mean, top);
  }
  return 0;
}
