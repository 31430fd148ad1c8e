// The look made by surface processes after the simulation (docs/model.md §14), on the refined
// surface, from its shape and its weathering history (SurfaceMesh::history):
//   stain     water from the sky runs down the fall line, is shed at overhang lips and drips to
//             the surface below, and leaves stain and desert varnish in streaks where it runs
//             (Dorsey, Pedersen and Hanrahan 1996; Chen et al. 2005); flat open tops stay clean
//   varnish   long-exposed rock darkens: G grows with the time the face has spent in the open
//             (its exposure age, less part of its time against colluvium; a fresh scar has had
//             none)
//   moisture  a damp band where rock meets colluvium or the ground, and in sheltered overhangs
//   dust      settles on ledges and in upward-facing hollows, where water does not wash it off
// Every value is a pure function of the meshes, the grid and the parameters: byte-identical at
// any thread count.
#pragma once

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"

namespace rockbake {

struct SurfaceLookParams {
  // Strengths, 0 (off) … 4 (LookParams): each scales its channel's amount, clamped to 0..1.
  double stain = 1.0, varnish = 1.0, moisture = 1.0, dust = 1.0;
  // The final grid, in the meshes' frame (before the pivot moves them): what shelters a point
  // from the sky, and where the ground and colluvium are.
  const VoxelRock* rock = nullptr;
};

// Fills meshes.rock.look and meshes.colluvium.look, one RGBA per vertex, each 0..1:
//   R exposure age (history[0]; a rockfall scar is as young as its fall), G stain and varnish,
//   B moisture, A dust.
// Reads positions, normals, triangles and the baked attributes (colluvium, curvature, altitude,
// history); the colluvium surface has no history (R 0, G 0, and A 0: it is itself the fine
// debris). Without a rock history (no look) neither mesh is touched; with one, params.rock is
// required (std::invalid_argument), as are a normal and a history per rock vertex.
void makeSurfaceLook(AssetMeshes& meshes, const SurfaceLookParams& params);

}  // namespace rockbake
