// Hand-built voxel grids and a weathering preset for the rockfall and
// colluvium tests (docs/model.md §6, §7).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "core/voxel_rock.h"
#include "preset/preset.h"
#include "test_support.h"

namespace rockbake::test {

// An all-air grid on the ground, h = 0.1, no margin.
inline VoxelRock emptyRock(int nx, int ny, int nz) {
  VoxelRock rock;
  rock.layout.nx = nx, rock.layout.ny = ny, rock.layout.nz = nz;
  rock.layout.h = 0.1;
  rock.layout.ground = true;
  rock.material.assign(rock.layout.cellCount(), Material::Air);
  rock.integrity = RowSpans(rock.layout, 1.f);
  rock.durability = RowSpans(rock.layout, 0.f);
  return rock;
}

inline void fill(VoxelRock& rock, std::array<int, 3> lo, std::array<int, 3> hi, Material m, float durability = 1.f) {
  for (int z = lo[2]; z < hi[2]; ++z)
    for (int y = lo[1]; y < hi[1]; ++y)
      for (int x = lo[0]; x < hi[0]; ++x) {
        const std::size_t i = rock.layout.index(x, y, z);
        rock.material[i] = m;
        rock.durability.set(i, m == Material::Rock ? durability : 0.f);
      }
}

inline Material at(const VoxelRock& rock, int x, int y, int z) {
  return rock.material[rock.layout.index(x, y, z)];
}

inline std::size_t solidCount(const VoxelRock& rock) {
  return rock.material.size() - rock.count(Material::Air);
}

// Independent check: every solid voxel is 6-connected to the layer z = 0.
// Solid cells not joined to the ground (z = 0) through face neighbours, by a plain flood fill.
inline std::size_t floatingCount(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::vector<std::uint8_t> reached(g.cellCount(), 0);
  std::deque<std::array<int, 3>> queue;
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x)
      if (at(rock, x, y, 0) != Material::Air) reached[g.index(x, y, 0)] = 1, queue.push_back({x, y, 0});
  while (!queue.empty()) {
    const auto [x, y, z] = queue.front();
    queue.pop_front();
    const int d[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    for (const auto& o : d) {
      const int a = x + o[0], b = y + o[1], c = z + o[2];
      if (!g.contains(a, b, c) || at(rock, a, b, c) == Material::Air || reached[g.index(a, b, c)]) continue;
      reached[g.index(a, b, c)] = 1;
      queue.push_back({a, b, c});
    }
  }
  std::size_t floating = 0;
  for (std::size_t i = 0; i < reached.size(); ++i) floating += rock.material[i] != Material::Air && !reached[i];
  return floating;
}

inline bool nothingFloats(const VoxelRock& rock) {
  return floatingCount(rock) == 0;
}

// A preset that weathers a rock with a soft neck, rockfall and colluvium on.
inline Preset neckPreset(std::uint64_t seed, RockfallMode mode) {
  Preset p = test::cubePreset(3.0, 36, 0.25);
  p.seed = seed;
  p.grid.size = {3.0, 3.0, 4.0};
  p.grid.ground = true;
  p.shape.kind = CylinderShape{0.9, 3.6};
  p.durability.graph.points = {{0.0, 1.5}, {0.35, 0.35}, {0.55, 0.35}, {0.65, 4.0}, {1.0, 4.0}};
  p.durability.graph.noise = {NoiseParams{0.3, 0.5, 2}, std::nullopt, std::nullopt, std::nullopt};
  p.bubbles[0].cavernous = 0.5;
  p.rockfall.mode = mode;
  p.colluvium = {0.6, 35.0, 0.05};
  p.stop.cycles = 40;
  return p;
}

}  // namespace rockbake::test
