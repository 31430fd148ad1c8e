// How different the individuals of each catalogue family are (docs/model.md §12,
// bench/README.md "Families"): for every entry of a library, N seeds from its
// first, each weathered at RESOLUTION, then
//   - the aligned IoU of every pair (sim/rock_measures.h): mean and largest;
//   - the spread (standard deviation) of Zingg's b/a and c/b over the seeds;
//   - the coefficient of variation of the rock volume;
//   - rock or colluvium voxels in the outermost ring of cells of the grid's sides, and how far
//     the colluvium reaches beyond the rock's footprint box;
//   - milliseconds weathering a seed, its grid's voxels, and the cost per grid voxel.
//   rockbake_family_variety [LIBRARY=presets/library.yaml] [RESOLUTION=48] [SEEDS=8]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "inputs/resolve_shape.h"
#include "preset/library.h"
#include "preset/load_preset.h"
#include "sim/rock_measures.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

namespace {

using namespace rockbake;

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}
double deviation(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return v.empty() ? 0.0 : std::sqrt(s / double(v.size()));
}

// Solid voxels (rock or colluvium) in the outermost ring of cells of the grid's four sides.
std::size_t onTheRim(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::size_t n = 0;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if ((x == 0 || y == 0 || x == g.nx - 1 || y == g.ny - 1) && rock.material[g.index(x, y, z)] != Material::Air)
          ++n;
  return n;
}

// How far the colluvium reaches beyond the rock's footprint box, at most over the four sides (world units).
double apronReach(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  int lo[2][2] = {{g.nx, g.ny}, {g.nx, g.ny}}, hi[2][2] = {{-1, -1}, {-1, -1}};
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const Material m = rock.material[g.index(x, y, z)];
        if (m == Material::Air) continue;
        const int k = m == Material::Rock ? 0 : 1;
        lo[k][0] = std::min(lo[k][0], x), lo[k][1] = std::min(lo[k][1], y);
        hi[k][0] = std::max(hi[k][0], x), hi[k][1] = std::max(hi[k][1], y);
      }
  if (hi[1][0] < 0 || hi[0][0] < 0) return 0.0;
  int reach = 0;
  for (int a = 0; a < 2; ++a) reach = std::max({reach, lo[0][a] - lo[1][a], hi[1][a] - hi[0][a]});
  return reach * g.h;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : std::string(ROCKBAKE_SOURCE_DIR) + "/presets/library.yaml";
  const int resolution = argc > 2 ? std::stoi(argv[2]) : 48;
  const int seeds = argc > 3 ? std::stoi(argv[3]) : 8;
  const Library library = loadLibrary(file);
  std::printf(
      "| preset | mean aligned IoU | largest | sd b/a | sd c/b | volume CV | on the rim | apron reach | ms / seed | "
      "Mvoxels | ns / voxel |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const LibraryEntry& entry : library.entries) {
    const std::uint64_t first = entry.seeds.empty() ? loadPreset(entry.preset_file).seed : entry.seeds.front();
    std::vector<VoxelRock> rocks;
    std::vector<double> ba, cb, volume;
    std::size_t rim = 0;
    double seconds = 0, cells = 0, reach = 0;
    for (int s = 0; s < seeds; ++s) {
      const Preset p = loadPreset(entry.preset_file, {{}, first + std::uint64_t(s), resolution});
      const auto start = std::chrono::steady_clock::now();
      rocks.push_back(weatherRock(buildInitialRock(resolveShape(p), p), p).rock);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const VoxelRock& r = rocks.back();
      cells += double(r.layout.cellCount());
      const auto axes = principalAxes(r);
      ba.push_back(axes[1] / axes[0]), cb.push_back(axes[2] / axes[1]);
      volume.push_back(double(r.count(Material::Rock)) * std::pow(r.layout.h, 3));
      rim += onTheRim(r);
      reach = std::max(reach, apronReach(r));
    }
    std::vector<double> iou;
    for (std::size_t i = 0; i < rocks.size(); ++i)
      for (std::size_t j = i + 1; j < rocks.size(); ++j) iou.push_back(alignedIoU(rocks[i], rocks[j]));
    double largest = 0;
    for (double x : iou) largest = std::max(largest, x);
    std::printf("| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %zu | %.2f | %.1f | %.2f | %.0f |\n", entry.name.c_str(),
                mean(iou), largest, deviation(ba), deviation(cb), deviation(volume) / mean(volume), rim, reach,
                1e3 * seconds / seeds, cells / seeds / 1e6, 1e9 * seconds / cells);
    std::fflush(stdout);
  }
}
