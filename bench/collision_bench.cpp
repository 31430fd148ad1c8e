// Collision hulls (docs/collision.md) on every shipped preset at its house
// resolution, against one convex hull of the whole rock (as it is, and cut
// to 64 vertices as the hulls are): hulls, vertices,
// coverage of the rock's voxel centres, air voxels claimed per rock voxel, and
// the time hullVoxels takes: wall-clock with all threads and CPU time on one
// thread (which a busy machine disturbs less), each the best of five runs.
//   rockbake_collision_bench BAKED [PRESET.yaml...]
// BAKED holds each preset's bake, BAKED/<name>/rock.vdb (bench/collision_bench.sh
// bakes them with --no-mesh); the presets default to the shipped ones, presets/*.yaml but base.yaml and library.yaml.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "collision/collision_hulls.h"
#include "collision/hull_coverage.h"
#include "collision/point_hull.h"
#include "export/vdb_file.h"
#include "platform/stopwatch.h"
#include "preset/load_preset.h"
#include "sim/grid_layout.h"

#include <tbb/global_control.h>

namespace {

using namespace rockbake;
namespace fs = std::filesystem;

// One hull of all the rock's voxel cubes, no vertex cap: of the corners of
// each x-run's end faces.
ConvexHull singleHull(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::vector<Vec3d> corners;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx;) {
        if (rock.material[g.index(x, y, z)] != Material::Rock) {
          ++x;
          continue;
        }
        int end = x + 1;
        while (end < g.nx && rock.material[g.index(end, y, z)] == Material::Rock) ++end;
        for (const int cx : {x, end})
          for (const int cy : {y, y + 1})
            for (const int cz : {z, z + 1}) corners.push_back({double(cx), double(cy), double(cz)});
        x = end;
      }
  const TriangulatedHull t = triangulateHull(corners);
  ConvexHull hull;
  hull.triangles = t.triangles;
  for (const Vec3d& v : t.vertices)
    hull.positions.push_back({g.origin[0] + g.h * v[0], g.origin[1] + g.h * v[1], g.origin[2] + g.h * v[2]});
  return hull;
}

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: rockbake_collision_bench BAKED [PRESET.yaml...]\n");
    return 2;
  }
  const fs::path baked = argv[1];
  std::vector<fs::path> presets(argv + 2, argv + argc);
  if (presets.empty()) {
    for (const auto& e : fs::directory_iterator(fs::path(ROCKBAKE_SOURCE_DIR) / "presets"))
      if (e.path().extension() == ".yaml" && e.path().filename() != "base.yaml" &&
          e.path().filename() != "library.yaml")
        presets.push_back(e.path());
    std::sort(presets.begin(), presets.end());
  }
  const CollisionParams params;  // the defaults: 16 hulls, 64 vertices
  std::printf(
      "| preset | rock voxels | hulls | vertices (most in a hull) | coverage | air per rock voxel | one hull: air | "
      "one hull of 64 vertices: air | wall, all threads | CPU, one thread |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n");
  for (const fs::path& file : presets) {
    const Preset preset = loadPreset(file);
    const VoxelRock rock = readRockVdb(baked / preset.name / "rock.vdb", computeGridLayout(preset));
    std::vector<ConvexHull> hulls;
    double wall = 1e30, cpu = 1e30;
    for (int run = 0; run < 5; ++run) {
      Stopwatch clock;
      hulls = hullVoxels(rock, Material::Rock, params);
      wall = std::min(wall, clock.elapsed());
    }
    {
      tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);  // all work on this thread
      for (int run = 0; run < 5; ++run) {
        const double start = threadCpuSeconds();
        hullVoxels(rock, Material::Rock, params);
        cpu = std::min(cpu, threadCpuSeconds() - start);
      }
    }
    std::size_t vertices = 0, most = 0;
    for (const ConvexHull& h : hulls) vertices += h.positions.size(), most = std::max(most, h.positions.size());
    const HullCoverage c = measureCoverage(rock, Material::Rock, hulls);
    const HullCoverage single = measureCoverage(rock, Material::Rock, {singleHull(rock)});
    const HullCoverage capped =
        measureCoverage(rock, Material::Rock, hullVoxels(rock, Material::Rock, {.max_hulls = 1}));
    std::printf("| %s | %zu | %zu | %zu (%zu) | %.2f %% | %.3f | %.3f | %.3f | %.3f s | %.3f s |\n",
                preset.name.c_str(), c.voxels, hulls.size(), vertices, most, 100.0 * c.coverage(), c.airPerVoxel(),
                single.airPerVoxel(), capped.airPerVoxel(), wall, cpu);
    std::fflush(stdout);
  }
}
