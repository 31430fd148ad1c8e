// Voxelizing a closed blockout (docs/model.md §8, `shape: {mesh}`) with OpenVDB's
// meshToLevelSet: a voxel is rock when its centre is inside the mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "core/voxel_rock.h"
#include "inputs/mesh_reader.h"

namespace rockbake {

// `mesh` in world units. Returns one flag per cell of `layout` (1 = inside).
std::vector<std::uint8_t> voxelizeMesh(const TriangleMesh& mesh, const GridLayout& layout);

}  // namespace rockbake
