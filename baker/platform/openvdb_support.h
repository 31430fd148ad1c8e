// Shared OpenVDB glue for the .cpp files that use OpenVDB (never include this
// from a widely included header: OpenVDB's headers are heavy).
#pragma once

#include <openvdb/openvdb.h>

#include "core/voxel_rock.h"

namespace rockbake {

// openvdb::initialize(), once per process, from any thread.
void initializeOpenVdb();

// The smoothed signed distance field the mesh stage polygonised the rock from
// (world units, negative inside, narrow band). Other headers name it only as an
// incomplete type, so they stay free of OpenVDB.
struct SmoothedSdf {
  openvdb::FloatGrid::Ptr grid;
};

// Index (i, j, k) → the voxel centre GridLayout::center(i, j, k) = origin + (index + ½) h.
openvdb::math::Transform::Ptr voxelCenterTransform(const GridLayout& layout);

}  // namespace rockbake
