// Stones laid on the debris apron (docs/model.md §13). Sizes follow a truncated power law
// (fragmentation: N(> s) ∝ s^-a between the preset's smallest and largest stone). Stones are
// fall-sorted: ranked by size, the larger a stone the further from the rock's foot it is sent
// (plus a seeded share of chance), as rockfall sorts talus. Each rests: tilted to the apron's
// slope under it, its long axis turned down the slope (give or take), lowered until it touches
// the apron or the ground and bedded in a tenth of a voxel. A stone that would overlap one
// already placed, touch the rock or leave the grid is tried elsewhere; one that finds no room
// after kTries sites is not placed. Serial, a pure function of its arguments: the same stones at
// any thread count.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/clast_set.h"
#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

struct ClastPlacement {
  const VoxelRock* rock = nullptr;                   // the final voxels (which columns hold rock)
  std::array<double, 3> pivot{};                     // world position of the meshes' origin
  const SurfaceMesh* colluvium = nullptr;            // LOD0's colluvium surface, about the pivot (may be empty)
  const std::vector<SurfaceMesh>* shapes = nullptr;  // the stone meshes (ClastSet::shapes)
  ClastParams params;
  std::uint64_t seed = 0;
};

inline constexpr int kClastTries = 40;

// The stones, largest first. None when the rock has no colluvium or no ground.
std::vector<ClastInstance> placeClasts(const ClastPlacement& placement);

}  // namespace rockbake
