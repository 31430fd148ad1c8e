#include "texture/texture_set.h"

#include <ctime>
#include <stdexcept>

#include "core/stopwatch.h"
#include "texture/ambient_occlusion.h"
#include "texture/bake_maps.h"
#include "texture/dilate_texels.h"
#include "texture/rasterize_uv.h"
#include "texture/ray_source.h"
#include "texture/tangents.h"
#include "texture/texture_files.h"
#include "texture/trace_texels.h"
#include "texture/uv_atlas.h"

namespace rockbake {

TextureSet bakeTextureSet(const std::vector<AssetMeshes>& lods, const AssetMeshes& source, LodLayout layout,
                          const TextureParams& params, const std::string& name, const std::filesystem::path& folder) {
  checkTextureParams(params);
  TextureSet set;
  Stopwatch clock;
  std::clock_t cpu = std::clock();
  const auto step = [&](const std::string& name) {
    const std::clock_t now = std::clock();
    set.steps.push_back({name, clock.lap(), double(now - cpu) / CLOCKS_PER_SEC});
    cpu = now;
  };
  const RaySource rays(source);
  step("ray scene");
  const RockLook look(params.seed, rays.radius(), params.voxel_size, source.durability_range);
  const double cage = params.cage > 0 ? params.cage : 0.1 * rays.radius();

  for (std::size_t k = 0; k < lods.size(); ++k) {
    const std::string lod = "lod" + std::to_string(k);
    UvAtlas atlas;
    if (layout == LodLayout::OwnAtlas) {
      atlas = buildUvAtlas(lods[k], params);
      step(lod + " atlas");
    } else {
      for (const SurfaceMesh* m : {&lods[k].rock, &lods[k].colluvium})
        if (!m->triangles.empty() && m->uvs.size() != m->positions.size())
          throw std::invalid_argument("bakeTextureSet: LOD" + std::to_string(k) + "'s " + m->name +
                                      " surface has no uvs in LOD0's layout");
      atlas.meshes = lods[k];
      atlas.texels_per_unit = texelDensity(lods[k], params.size);
    }
    computeTangents(atlas.meshes.rock);
    computeTangents(atlas.meshes.colluvium);
    step(lod + " tangents");
    TexelMap texels = rasterizeUv(atlas.meshes, params.size);
    dilateTexels(texels);
    const TexelHits hits = traceTexels(atlas.meshes, texels, rays, cage);
    set.missed += hits.missed;
    step(lod + " rays");

    const LodBake bake{&atlas.meshes, &texels, &hits, &source};
    const bool own_maps = k == 0 || layout == LodLayout::OwnAtlas;  // else LOD0's base colour, ORM and mask serve
    std::array<std::vector<float>, 2> occlusion;
    if (own_maps && wantsMap(params, TextureMap::Orm)) {
      occlusion = vertexOcclusion(atlas.meshes, rays, params);
      step(lod + " occlusion");
    }
    const int suffix = k == 0 ? -1 : int(k);
    const auto record = [&](TextureMap map, int channels, int bits, const char* space) {
      set.files.push_back({textureFileName(name, map, map == TextureMap::Normal ? int(k) : suffix), map, int(k),
                           params.size, channels, bits, space});
      return folder / set.files.back().file;
    };
    // Each map is made, then written and freed, before the next: one map in memory at a time.
    const auto timed = [&](TextureMap map, auto&& image, auto&& write) {
      step(lod + " " + mapName(map));
      write(image);
      step(lod + " " + mapName(map) + " file");
    };
    for (TextureMap map : params.maps) {
      if (map != TextureMap::Normal && !own_maps) continue;
      switch (map) {
        case TextureMap::Normal:
          timed(map, bakeNormalMap(bake),
                [&](const auto& image) { writeTexturePng(record(map, 3, 16, "linear"), image); });
          break;
        case TextureMap::BaseColor:
          timed(map, bakeBaseColor(bake, look),
                [&](const auto& image) { writeTexturePng(record(map, 3, 8, "srgb"), image, true); });
          break;
        case TextureMap::Orm:
          timed(map, bakeOrm(bake, occlusion, look),
                [&](const auto& image) { writeTexturePng(record(map, 3, 8, "linear"), image, false); });
          break;
        case TextureMap::Mask:
          timed(map, bakeMask(bake, look),
                [&](const auto& image) { writeTexturePng(record(map, 4, 8, "linear"), image, false); });
          break;
        case TextureMap::Height:
          if (k == 0)
            timed(map, bakeHeight(bake),
                  [&](const auto& image) { writeTextureExr(record(map, 1, 32, "linear"), image); });
          break;
      }
    }
    set.charts.push_back(atlas.charts);
    set.texels_per_unit.push_back(atlas.texels_per_unit);
    set.lods.push_back(std::move(atlas.meshes));
  }
  return set;
}

}  // namespace rockbake
