// The mesh stage takes the simulation's VoxelRock and gives AssetMeshes: this
// file extracts the surfaces; bake_attributes.h samples and colours them,
// subdivide.h refines them, simplify_lods.h makes the LODs.
//
// Extraction (SPEC §3): the rock and the colluvium of a voxel grid as separate
// closed, 2-manifold, outward-oriented surfaces, quad-dominant.
//
// Each material's occupancy becomes a narrow-band level set (zero crossing on
// the voxel faces), smoothed by `smoothing` passes of a width-1 Gaussian
// level-set filter, and polygonised at the zero crossing (OpenVDB, TBB-parallel).
// On a grid with ground, the lowest voxel layers are mirrored below z = 0
// before smoothing (walls run straight into the ground) and the smoothed field
// is intersected with the half-space z >= 0, so a surface resting on the
// ground closes with a flat cap exactly on z = 0 (its rim bevelled by at most
// half a voxel) and no vertex lies below it. The ground itself is not meshed.
#pragma once

#include <memory>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"

namespace rockbake {

struct SmoothedSdf;  // io/openvdb_support.h

struct ExtractParams {
  double smoothing = 1.0;  // 0..4 Gaussian passes (rounded to the nearest whole pass)
};

// Positions (world units, z up), triangles and quads of both surfaces, no
// attributes or normals yet; an empty SurfaceMesh where a material is absent.
// With `rock_sdf`, also hands back the rock's smoothed, ground-clipped level set
// (index space = voxel (x, y, z), as the mesh's zero crossing; null without rock),
// so the VDB export carries the field the mesh was made from.
// Throws std::runtime_error if OpenVDB fails.
AssetMeshes extractSurfaces(const VoxelRock& rock, const ExtractParams& params,
                            std::shared_ptr<const SmoothedSdf>* rock_sdf = nullptr);

}  // namespace rockbake
