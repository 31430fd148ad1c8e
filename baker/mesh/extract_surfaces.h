// The mesh stage takes the simulation's VoxelRock and gives AssetMeshes: this
// file extracts the surfaces; bake_attributes.h samples and colours them,
// subdivide.h refines them, simplify_lods.h makes the LODs.
//
// Extraction (docs/meshes.md): the rock and the colluvium of a voxel grid as separate
// closed, 2-manifold, outward-oriented surfaces, quad-dominant.
//
// Each material's occupancy becomes a narrow-band level set (zero crossing on
// the voxel faces), smoothed by `smoothing` passes of a width-1 Gaussian
// level-set filter (one renormalisation sweep between its box passes, three
// after the last), and polygonised at the zero crossing (OpenVDB, TBB-parallel).
// Every voxel's sample keeps its side after smoothing; one that smoothing
// moved across (a voxel-thin part of the rock) is held a quarter voxel deep,
// with the distance bound restored around it, so such a part stays about half
// a voxel thick instead of a sliver no mesh can follow without folding. The
// colluvium's voxel-thin parts are left to the smoothing (a lone voxel or a
// one-voxel veneer would stand as a plate).
// On a grid with ground, the lowest voxel layers are mirrored below z = 0
// before smoothing (walls run straight into the ground) and the smoothed field
// is intersected with the half-space z >= 0, so a surface resting on the
// ground closes with a flat cap exactly on z = 0 (its rim bevelled by at most
// half a voxel) and no vertex lies below it. The ground itself is not meshed.
#pragma once

#include <array>
#include <memory>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"

namespace rockbake {

struct SmoothedSdf;  // platform/openvdb_support.h

struct ExtractParams {
  double smoothing = 1.0;  // 0..4 Gaussian passes (rounded to the nearest whole pass)
  // The studio's live preview: the band is renormalised once after every box
  // pass, with first-order differences instead of fifth-order ones (WENO5),
  // in a two-voxel band.
  // Its vertices lie within half a voxel of the bake's surface (about a
  // fiftieth on average); every voxel keeps its side, as in the bake.
  bool preview = false;
};

// Positions (world units, z up), triangles and quads of both surfaces, no
// attributes or normals yet; an empty SurfaceMesh where a material is absent.
// With `rock_sdf`, also hands back the rock's smoothed, ground-clipped level set
// (index space = voxel (x, y, z), as the mesh's zero crossing; null without rock),
// so the VDB export carries the field the mesh was made from.
// Throws std::runtime_error if OpenVDB fails.
AssetMeshes extractSurfaces(const VoxelRock& rock, const ExtractParams& params,
                            std::shared_ptr<const SmoothedSdf>* rock_sdf = nullptr);

// The asset's pivot (docs/meshes.md, Megascans' convention): the centre of the solid
// voxels' (rock and colluvium) footprint, on the ground (z = 0; without ground,
// the lowest voxel's floor). World units. Meshes, rock.vdb and the scene are
// all written relative to it. The grid's centre when nothing is solid.
// `sink` (world units, >= 0) raises the pivot by that much: the asset stands that deep in the
// ground plane (mesh.sink).
std::array<double, 3> footprintPivot(const VoxelRock& rock, double sink = 0.0);

// How deep a set dresser should sink the rock (world units): at least a voxel, so that uneven
// terrain never shows a gap under it, and deeper where the rock stands on a foot narrower than
// itself: up to the lowest layer whose rock section is 60 % of the widest section in the lower
// third of the rock's height. 0 without ground or rock.
double suggestedBurialDepth(const VoxelRock& rock);

// mesh.sink resolved: `sink` itself, or suggestedBurialDepth for MeshParams::kSinkSuggested.
double sinkDepth(const VoxelRock& rock, double sink);

// Translates both surfaces and the bounds by -pivot.
void movePivot(AssetMeshes& meshes, const std::array<double, 3>& pivot);

// Moves every vertex not on the ground cap onto the zero crossing of `field`
// (up to six Newton steps along the field's gradient, trilinear samples; where
// they leave it more than 0.02 voxels off, the nearest crossing found along
// the gradient, the normal or towards a nearby sample of the other sign,
// bisected), so a refined surface lies on the level set it was extracted
// from, as rock.vdb records it. Normals are recomputed.
void projectOntoField(SurfaceMesh& mesh, const SmoothedSdf* field, bool ground);

// Smoothing rounds convex rock off: the surface encloses less than its voxels.
// Moves every vertex of a triangle mesh with normals, except those on the
// ground cap (z = 0 with `ground`), along its normal by one distance delta
// (world units, |delta| <= max_offset) so that it encloses `target_volume`,
// recomputes the normals and returns delta. No vertex goes below z = 0.
double matchVolume(SurfaceMesh& mesh, double target_volume, double max_offset, bool ground);

// `field` with its zero crossing moved outwards by delta (phi - delta), to
// follow a surface moved by matchVolume. With `ground`, the clip at z = 0 is
// kept in place: max(phi - delta, -z) where extractSurfaces clipped.
std::shared_ptr<const SmoothedSdf> offsetField(const std::shared_ptr<const SmoothedSdf>& field, double delta,
                                               bool ground);

}  // namespace rockbake
