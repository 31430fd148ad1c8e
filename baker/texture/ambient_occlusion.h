// Ambient occlusion against the bake source (docs/textures.md), per vertex of the mesh whose
// ORM map is baked (LOD0, or a LOD with an atlas of its own): the share of `params.ao_rays`
// cosine-weighted rays over the vertex's normal hemisphere that leave both surfaces of the
// source without a hit within `params.ao_distance` (0: any distance), 1 open … 0 closed. The
// rays are a stratified set (a radical-inverse sequence) turned by an offset hashed from
// (`seed`, surface, the vertex's position), so the copies of a vertex a seam split agree, and
// the same at any thread count; they go out in packets of RaySource::kPacket.
//
// Per vertex, interpolated over the LOD's triangles, rather than per texel: occlusion varies
// slowly, and the LOD's vertices are where its shape changes (the simplifier keeps them
// dense in crevices). A LOD's vertices are source vertices (the simplifier only removes
// vertices), so each lies on the source. The cost follows the LOD's vertices times the rays:
// goblin's LOD0, 18,000 vertices, casts 0.6 M rays where every texel at 2048 would cast 75 M
// and every source vertex 10 M.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.h"
#include "texture/ray_source.h"
#include "texture/texture_params.h"

namespace rockbake {

// [0]: per vertex of at.rock, [1]: of at.colluvium (with normals). TBB-parallel over vertices.
std::array<std::vector<float>, 2> vertexOcclusion(const AssetMeshes& at, const RaySource& source,
                                                  const TextureParams& params, std::uint64_t seed);

}  // namespace rockbake
