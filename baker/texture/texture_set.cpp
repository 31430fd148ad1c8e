#include "texture/texture_set.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <functional>
#include <memory>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <stdexcept>
#include <string_view>
#include <variant>

#include "platform/side_by_side.h"
#include "platform/stopwatch.h"
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
namespace {

// Hands the heap's free pages back to the system. What the atlas's solvers free on a hero's
// LOD0 the allocator would otherwise keep, while the texel map and the hits that follow are
// large blocks mapped afresh: without this the two add up (75 MiB of the set's peak there).
void releaseFreedHeap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace

namespace {

// Occlusion at or below this (ORM's R: 1 open, 0 closed) counts as hidden.
constexpr float kHiddenOcclusion = 0.1f;

// Per triangle: on the ground plane facing down (a ground cap), or occluded at all three corners.
HiddenTriangles hiddenSurface(const AssetMeshes& lod, const std::array<std::vector<float>, 2>& occlusion,
                              double ground) {
  HiddenTriangles hidden;
  const std::array<const SurfaceMesh*, 2> surfaces{&lod.rock, &lod.colluvium};
  for (std::size_t s = 0; s < 2; ++s) {
    const SurfaceMesh& m = *surfaces[s];
    hidden[s].assign(m.triangles.size(), 0);
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const auto& tri = m.triangles[t];
      const auto& a = m.positions[tri[0]];
      const auto& b = m.positions[tri[1]];
      const auto& c = m.positions[tri[2]];
      const double eps = 1e-5 * (1.0 + std::abs(ground));
      const bool on_plane = std::max({double(a[2]), double(b[2]), double(c[2])}) <= ground + eps;
      const double nz = (double(b[0]) - a[0]) * (double(c[1]) - a[1]) - (double(b[1]) - a[1]) * (double(c[0]) - a[0]);
      const auto& o = occlusion[s];
      const bool dark = o.size() == m.positions.size() && o[tri[0]] <= kHiddenOcclusion &&
                        o[tri[1]] <= kHiddenOcclusion && o[tri[2]] <= kHiddenOcclusion;
      hidden[s][t] = (on_plane && nz < 0) || dark;
    }
  }
  return hidden;
}

// Records each step of the set in TextureSet::steps: the wall-clock and CPU seconds since the last.
class StepTimer {
 public:
  explicit StepTimer(PhaseTimes& steps) : steps_(steps) {}
  void operator()(const std::string& name) {
    const std::clock_t now = std::clock();
    steps_.add(name, clock_.lap(), double(now - cpu_) / CLOCKS_PER_SEC);
    cpu_ = now;
  }

 private:
  PhaseTimes& steps_;
  Stopwatch clock_;
  std::clock_t cpu_ = std::clock();
};

// What a LOD's maps read besides its LodBake.
struct MapInputs {
  const TextureSetRequest& request;
  const RockLook& look;
  const std::array<std::vector<float>, 2>& occlusion;  // per vertex of the LOD's atlas: the ORM's
  const GroundMask& contact;                           // the mask's alpha
};

template <class T>
using MapBaker = TextureImage<T> (*)(const LodBake& bake, const MapInputs& inputs);

// One row per map kind (docs/textures.md §5): what bakes it and its file's format.
struct MapKind {
  TextureMap map;
  std::variant<MapBaker<std::uint8_t>, MapBaker<std::uint16_t>, MapBaker<float>> bake;
  int channels;
  int bits;                  // per channel: 8, 16 or 32 (float)
  const char* colour_space;  // "srgb" or "linear"
  bool lod0_only;            // the height is LOD0's displacement alone
};

const MapKind kMapKinds[] = {
    {TextureMap::Normal,
     [](const LodBake& b, const MapInputs& in) { return bakeNormalMap(b, in.request.directx_normals); }, 3, 16,
     "linear", false},
    {TextureMap::BaseColor, [](const LodBake& b, const MapInputs& in) { return bakeBaseColor(b, in.look); }, 3, 8,
     "srgb", false},
    {TextureMap::Orm, [](const LodBake& b, const MapInputs& in) { return bakeOrm(b, in.occlusion, in.look); }, 3, 8,
     "linear", false},
    {TextureMap::Height, [](const LodBake& b, const MapInputs&) { return bakeHeight(b); }, 1, 32, "linear", true},
    {TextureMap::Mask, [](const LodBake& b, const MapInputs& in) { return bakeMask(b, in.look, in.contact); }, 4, 8,
     "linear", false},
    {TextureMap::History, [](const LodBake& b, const MapInputs&) { return bakeHistory(b); }, 4, 8, "linear", false},
};

const MapKind& mapKind(TextureMap map) {
  for (const MapKind& kind : kMapKinds)
    if (kind.map == map) return kind;
  throw std::logic_error("texture set: no row for the map " + mapName(map));
}

// The bits per channel `kind`'s file has at `precision` (docs/textures.md §6): compact stores the
// normals in 8 bits and the height in half floats, full as they are made (16 bits, 32-bit floats).
int fileBits(const MapKind& kind, MapPrecision precision) {
  return precision == MapPrecision::Compact && kind.bits > 8 ? kind.bits / 2 : kind.bits;
}

// The height's step in a compact file (docs/textures.md §6): the largest power of two within
// 1/256 of a voxel. Half floats near zero keep detail a thousand times finer than that, which
// the refined surface does not have and ZIP cannot compress; multiples of a power of two are
// exact in a half up to 2048 steps (beyond, the half's own rounding is the coarser). 0 (no
// step) without a voxel size.
double compactHeightStep(double voxel_size) {
  return voxel_size > 0 ? std::ldexp(1.0, int(std::floor(std::log2(voxel_size / 256.0)))) : 0.0;
}

// The writers of texture_files.h, by the map's pixel type.
void writeMap(const std::filesystem::path& file, const MapKind& kind, int size, int rows, const TextureSetRequest&,
              const TextureBands<std::uint8_t>& made) {
  writeTexturePng(file, size, kind.channels, std::string_view(kind.colour_space) == "srgb", rows, made);
}
void writeMap(const std::filesystem::path& file, const MapKind& kind, int size, int rows,
              const TextureSetRequest& request, const TextureBands<std::uint16_t>& made) {
  if (fileBits(kind, request.params.precision) == 16) return writeTexturePng(file, size, rows, made);
  // 8 bits, rounded to the nearest: 1/255 steps keep a normal within 0.23° (docs/textures.md §6).
  writeTexturePng(file, size, kind.channels, false, rows, [&made](int first, int last) {
    const TextureImage<std::uint16_t> wide = made(first, last);
    TextureImage<std::uint8_t> narrow{wide.size, wide.channels, std::vector<std::uint8_t>(wide.pixels.size()),
                                      wide.first_row};
    for (std::size_t i = 0; i < wide.pixels.size(); ++i)
      narrow.pixels[i] = std::uint8_t((std::uint32_t(wide.pixels[i]) * 255u + 32767u) / 65535u);
    return narrow;
  });
}
void writeMap(const std::filesystem::path& file, const MapKind& kind, int size, int rows,
              const TextureSetRequest& request, const TextureBands<float>& made) {
  const bool half = fileBits(kind, request.params.precision) == 16;
  const double step = half ? compactHeightStep(request.voxel_size) : 0.0;
  if (step == 0.0) return writeTextureExr(file, size, rows, made, half);
  writeTextureExr(
      file, size, rows,
      [&made, step](int first, int last) {
        TextureImage<float> band = made(first, last);
        for (float& v : band.pixels) v = float(std::round(v / step) * step) + 0.0f;  // + 0: no −0
        return band;
      },
      true);
}

// Every LOD's atlas, side by side: each LOD has its own (docs/textures.md §7), and one atlas
// alone leaves a core idle where its flattening and packing go one step at a time. Each LOD's
// map size goes to `sizes`: lodMapSize, no larger than `useful` unless the gutters need it.
std::vector<UvAtlas> buildLodAtlases(const std::vector<AssetMeshes>& lods, const TextureSetRequest& request, int useful,
                                     const std::vector<HiddenTriangles>& hidden, std::vector<int>& sizes) {
  const TextureParams& params = request.params;
  std::vector<UvAtlas> atlases(lods.size());
  allSideBySide(lods.size(), [&](std::size_t k) {
    const int asked = lodMapSize(params, int(k));
    sizes[k] = std::min(asked, useful);
    try {
      atlases[k] = buildUvAtlas(lods[k], sizes[k], params.padding, request.ground ? &hidden[k] : nullptr);
    } catch (const ChartsDoNotFit&) {
      if (sizes[k] == asked) throw;
      sizes[k] = asked;  // the gutters need the room the preset gave them
      atlases[k] = buildUvAtlas(lods[k], sizes[k], params.padding, request.ground ? &hidden[k] : nullptr);
    }
  });
  return atlases;
}

// The maps a LOD's set has, in order: params.maps, and the History map with a look.
std::vector<TextureMap> lodMaps(const TextureParams& params, const AssetMeshes& source) {
  std::vector<TextureMap> maps = params.maps;
  if (!source.rock.look.empty()) maps.push_back(TextureMap::History);  // a look's own map
  return maps;
}

// LOD k's maps of `maps` (in that order), their files listed in `files`. Each map is made,
// then written and freed, before the next: one map in memory at a time, or one band of it.
void writeLodMaps(const TextureSetRequest& request, std::size_t k, int size, const LodBake& bake,
                  const MapInputs& inputs, const std::vector<TextureMap>& maps, std::vector<TextureFile>& files,
                  StepTimer& step) {
  const std::string lod = "lod" + std::to_string(k);
  const bool banded = request.whole_map_size <= 0 || size > request.whole_map_size;
  const int rows = banded ? (request.band_rows > 0 ? request.band_rows : kBandRows) : size;
  for (TextureMap map : maps) {
    const MapKind& kind = mapKind(map);
    if (kind.lod0_only && k > 0) continue;
    step(lod + " " + mapName(map));  // the time until here: the map's own is in its file's step
    const int suffix = map == TextureMap::Normal || k > 0 ? int(k) : -1;
    const MapPrecision precision = request.params.precision;
    files.push_back({textureFileName(request.name, map, suffix), map, int(k), size, kind.channels,
                     fileBits(kind, precision), kind.colour_space});
    const std::filesystem::path file = request.folder / files.back().file;
    std::visit(
        [&](auto bake_map) {
          using Image = decltype(bake_map(bake, inputs));
          const std::function<Image(int, int)> bands = [&bake, &inputs, bake_map](int first, int last) {
            LodBake band = bake;
            band.first_row = first, band.last_row = last;
            return bake_map(band, inputs);
          };
          writeMap(file, kind, size, rows, request, bands);
        },
        kind.bake);
    step(lod + " " + mapName(map) + " file");
  }
}

// The ray scene a LOD's texels are traced to, and whether to free it after the LOD's last trace
// (LOD0's: its maps, the largest, are then made without it).
struct LodRays {
  std::unique_ptr<RaySource>& scene;
  bool free_after;
  double cage;
};

// LOD k's maps, lodMaps in that order, into `files`: the colour maps at colourMapSize first, from
// texels and rays of their own, freed before the relief maps' at the LOD's `size` are made. Returns
// the size the LOD's maps are listed at (the colour maps' when it has no relief map) and adds the
// misses of its texels at that size to `missed`.
int writeLodMapSet(const TextureSetRequest& request, std::size_t k, int size, const UvAtlas& atlas,
                   const AssetMeshes& source, LodRays rays, const MapInputs& inputs, std::vector<TextureFile>& files,
                   std::size_t& missed, StepTimer& step) {
  const std::vector<TextureMap> maps = lodMaps(request.params, source);
  std::vector<TextureMap> colour_maps, relief_maps;
  const int colour_size = colourMapSize(request.params, size, atlas.texels_per_unit * request.voxel_size);
  for (const TextureMap map : maps) (colour_size < size && isColourMap(map) ? colour_maps : relief_maps).push_back(map);
  // One pass: the texels at `at`, dilated, traced, then `which` made from them.
  const auto pass = [&](int at, const std::vector<TextureMap>& which, const char* step_name, bool last) {
    TexelMap texels = rasterizeUv(atlas.meshes, at);
    dilateTexels(texels);
    const TexelHits hits = traceTexels(atlas.meshes, texels, *rays.scene, rays.cage);
    if (last) missed += hits.missed;
    step("lod" + std::to_string(k) + step_name);
    if (last && rays.free_after) rays.scene.reset();
    writeLodMaps(request, k, at, {&atlas.meshes, &texels, &hits, &source}, inputs, which, files, step);
  };
  if (!colour_maps.empty()) pass(colour_size, colour_maps, " colour rays", relief_maps.empty());
  if (!relief_maps.empty()) pass(size, relief_maps, " rays", true);
  // Listed in the set's order, whichever size made them first.
  std::stable_sort(files.begin(), files.end(), [&maps](const TextureFile& a, const TextureFile& b) {
    return std::find(maps.begin(), maps.end(), a.map) < std::find(maps.begin(), maps.end(), b.map);
  });
  return relief_maps.empty() ? colour_size : size;
}

}  // namespace

TextureSet bakeTextureSet(const std::vector<AssetMeshes>& lods, const AssetMeshes& source,
                          const TextureSetRequest& request) {
  const TextureParams& params = request.params;
  checkTextureParams(params);
  std::filesystem::create_directories(request.folder);
  TextureSet set;
  StepTimer step(set.steps);
  auto rays = std::make_unique<RaySource>(source);
  step("ray scene");
  const double radius = rays->radius();
  const RockLook look(request.seed, radius, request.voxel_size, source.durability_range, request.varied);
  const double cage = params.cage > 0 ? params.cage : 0.1 * radius;
  // Where the asset meets the ground, for the mask's alpha (bake_maps.h).
  const GroundMask contact =
      wantsMap(params, TextureMap::Mask) ? groundMask(source, request.ground, request.voxel_size) : GroundMask{};

  // No LOD's maps larger than the source can fill (texture_params.h).
  const int useful = usefulMapSize(source.rock.triangles.size() + source.colluvium.triangles.size());
  std::vector<int> sizes(lods.size());

  // Each LOD's occlusion, per vertex, before its atlas: it finds the hidden surface (uv_atlas.h: the
  // ground caps and what no occlusion ray leaves) and is the ORM's. A vertex's rays are hashed from
  // its position, so its copies along the seams would cast the same ones: they take its value.
  std::vector<std::array<std::vector<float>, 2>> lod_occlusion(lods.size());
  std::vector<HiddenTriangles> hidden(lods.size());
  if (wantsMap(params, TextureMap::Orm) || request.ground) {
    for (std::size_t k = 0; k < lods.size(); ++k) {
      lod_occlusion[k] = vertexOcclusion(lods[k], *rays, params, request.seed);
      if (request.ground) hidden[k] = hiddenSurface(lods[k], lod_occlusion[k], *request.ground);
    }
    step("occlusion");
  }

  std::vector<UvAtlas> atlases = buildLodAtlases(lods, request, useful, hidden, sizes);
  releaseFreedHeap();
  step("atlases");
  const int lod_count = int(lods.size());
  int lods_done = 0;
  if (request.progress) request.progress(-1, 0, 0, lod_count);

  // LOD0 last: its rays are the last the ray scene serves, so the scene is gone before its
  // maps, the largest, are made (docs/textures.md §11). The files are listed LOD by LOD.
  std::vector<std::vector<TextureFile>> files(lods.size());
  std::vector<std::size_t> order;
  for (std::size_t k = 1; k < lods.size(); ++k) order.push_back(k);
  if (!lods.empty()) order.push_back(0);
  for (const std::size_t k : order) {
    const std::string lod = "lod" + std::to_string(k);
    const int size = sizes[k];
    UvAtlas& atlas = atlases[k];
    computeTangents(atlas.meshes.rock);
    computeTangents(atlas.meshes.colluvium);
    step(lod + " tangents");
    std::array<std::vector<float>, 2> occlusion;
    if (wantsMap(params, TextureMap::Orm))
      for (std::size_t s = 0; s < 2; ++s)
        for (const std::uint32_t v : atlas.source_vertex[s]) occlusion[s].push_back(lod_occlusion[k][s][v]);
    const MapInputs inputs{request, look, occlusion, contact};
    sizes[k] =
        writeLodMapSet(request, k, size, atlas, source, {rays, k == 0, cage}, inputs, files[k], set.missed, step);
    if (request.progress) request.progress(int(k), sizes[k], ++lods_done, lod_count);
  }
  for (UvAtlas& atlas : atlases) {
    set.charts.push_back(atlas.charts);
    set.texels_per_unit.push_back(atlas.texels_per_unit);
    set.coverage.push_back(uvCoverage(atlas.meshes));
    set.lods.push_back(std::move(atlas.meshes));
  }
  set.sizes = sizes;
  for (std::vector<TextureFile>& lod : files) set.files.insert(set.files.end(), lod.begin(), lod.end());
  return set;
}

const TextureFile* findTextureFile(const TextureSet& set, int lod, TextureMap map) {
  for (const TextureFile& f : set.files)
    if (f.lod == lod && f.map == map) return &f;
  return nullptr;
}

}  // namespace rockbake
