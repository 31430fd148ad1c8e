// Ambient occlusion of the bake source (docs/textures.md), per source vertex: the share of
// `params.ao_rays` cosine-weighted rays over the vertex's normal hemisphere that leave both
// surfaces without a hit within `params.ao_distance` (0: any distance), 1 open … 0 closed.
// The rays are a stratified set (a radical-inverse sequence) turned by a per-vertex offset
// hashed from (seed, surface, vertex): seeded, and the same at any thread count.
//
// Per vertex rather than per texel: the source is finer than the maps' texels on every
// shipped preset (goblin: about 0.02 world units between source vertices, 0.005 per texel
// at 2048), occlusion varies slowly across it, and one set of values serves every map and
// every LOD, so its cost follows the source's vertices, not texels × rays. The maps read it
// interpolated at each texel's hit on the source.
#pragma once

#include <array>
#include <vector>

#include "core/surface_mesh.h"
#include "texture/ray_source.h"
#include "texture/texture_params.h"

namespace rockbake {

// [0]: per vertex of source.rock, [1]: of source.colluvium. TBB-parallel over vertices.
std::array<std::vector<float>, 2> vertexOcclusion(const AssetMeshes& source, const RaySource& rays,
                                                  const TextureParams& params);

}  // namespace rockbake
