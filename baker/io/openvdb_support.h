// Shared OpenVDB glue for the .cpp files that use OpenVDB (never include this
// from a widely included header: OpenVDB's headers are heavy).
#pragma once

#include <openvdb/openvdb.h>

#include "sim/voxel_rock.h"

namespace rockbake {

// openvdb::initialize(), once per process, from any thread.
void initializeOpenVdb();

// Index (i, j, k) → the voxel centre GridLayout::center(i, j, k) = origin + (index + ½) h.
openvdb::math::Transform::Ptr voxelCenterTransform(const GridLayout& layout);

}  // namespace rockbake
