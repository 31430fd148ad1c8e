#include "texture/texture_set.h"

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

TextureSet bakeTextureSet(const std::vector<AssetMeshes>& lods, const AssetMeshes& source, const TextureParams& params,
                          const std::string& name, const std::filesystem::path& folder) {
  checkTextureParams(params);
  TextureSet set;
  Stopwatch clock;
  const RaySource rays(source);
  set.seconds.emplace_back("ray scene", clock.lap());
  std::array<std::vector<float>, 2> occlusion;
  if (wantsMap(params, TextureMap::Orm)) {
    occlusion = vertexOcclusion(source, rays, params);
    set.seconds.emplace_back("occlusion", clock.lap());
  }
  const RockLook look(params.seed, rays.radius(), params.voxel_size, source.durability_range);
  const double cage = params.cage > 0 ? params.cage : 0.1 * rays.radius();

  for (std::size_t k = 0; k < lods.size(); ++k) {
    const std::string lod = "lod" + std::to_string(k);
    UvAtlas atlas = buildUvAtlas(lods[k], params);
    set.seconds.emplace_back(lod + " atlas", clock.lap());
    computeTangents(atlas.meshes.rock);
    computeTangents(atlas.meshes.colluvium);
    set.seconds.emplace_back(lod + " tangents", clock.lap());
    TexelMap texels = rasterizeUv(atlas.meshes, params.size);
    dilateTexels(texels);
    const TexelHits hits = traceTexels(atlas.meshes, texels, rays, cage);
    set.missed += hits.missed;
    set.seconds.emplace_back(lod + " rays", clock.lap());

    const LodBake bake{&atlas.meshes, &texels, &hits, &source};
    const int suffix = k == 0 ? -1 : int(k);
    const auto record = [&](TextureMap map, int channels, int bits, const char* space) {
      set.files.push_back({textureFileName(name, map, map == TextureMap::Normal ? int(k) : suffix), map, int(k),
                           params.size, channels, bits, space});
      return folder / set.files.back().file;
    };
    for (TextureMap map : params.maps) {
      switch (map) {
        case TextureMap::Normal:
          writeTexturePng(record(map, 3, 16, "linear"), bakeNormalMap(bake));
          break;
        case TextureMap::BaseColor:
          writeTexturePng(record(map, 3, 8, "srgb"), bakeBaseColor(bake, look), true);
          break;
        case TextureMap::Orm:
          writeTexturePng(record(map, 3, 8, "linear"), bakeOrm(bake, occlusion, look), false);
          break;
        case TextureMap::Mask:
          writeTexturePng(record(map, 4, 8, "linear"), bakeMask(bake, look), false);
          break;
        case TextureMap::Height:
          if (k == 0) writeTextureExr(record(map, 1, 32, "linear"), bakeHeight(bake));
          break;
      }
      set.seconds.emplace_back(lod + " " + mapName(map), clock.lap());
    }
    set.charts.push_back(atlas.charts);
    set.texels_per_unit.push_back(atlas.texels_per_unit);
    set.lods.push_back(std::move(atlas.meshes));
  }
  return set;
}

}  // namespace rockbake
