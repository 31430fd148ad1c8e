// How far LOD0 lies from the surface it was simplified from:
// rock.vdb's rock_sdf sampled (trilinear) at rock.ply's vertices, in voxels.
// Bake with `--set mesh.detail=null` so the field and the surface agree.
//   lod0_error ASSET_DIR  → "vertices N mean M p99 P max X (voxels)"
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "inputs/mesh_reader.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: lod0_error ASSET_DIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  openvdb::initialize();
  openvdb::io::File vdb((dir / "rock.vdb").string());
  vdb.open(false);
  const auto sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(vdb.readGrid("rock_sdf"));
  vdb.close();
  const double h = sdf->voxelSize()[0];
  const rockbake::TriangleMesh mesh = rockbake::readTriangleMesh(dir / "rock.ply");
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*sdf);
  std::vector<double> phi;
  std::vector<std::pair<double, std::size_t>> worst;
  for (const auto& p : mesh.positions) {
    phi.push_back(std::abs(sampler.wsSample(openvdb::Vec3R(p[0], p[1], p[2]))) / h);
    worst.push_back({phi.back(), worst.size()});
  }
  std::sort(phi.begin(), phi.end());
  std::sort(worst.rbegin(), worst.rend());
  for (std::size_t i = 0; i < std::min<std::size_t>(5, worst.size()); ++i) {  // where to look first
    const auto& p = mesh.positions[worst[i].second];
    std::printf("far: %.3f voxels at (%.4f, %.4f, %.4f)\n", worst[i].first, p[0], p[1], p[2]);
  }
  double mean = 0;
  for (double v : phi) mean += v / double(phi.size());
  std::printf("vertices %zu mean %.4f p99 %.4f max %.4f (voxels)\n", phi.size(), mean, phi[phi.size() * 99 / 100],
              phi.back());
  return 0;
}
