#include "core/voxel_rock.h"

#include <algorithm>

namespace rockbake {

std::size_t VoxelRock::count(Material m) const {
  return std::size_t(std::count(material.begin(), material.end(), m));
}

}  // namespace rockbake
