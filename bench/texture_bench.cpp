// The texture stage on a real asset (docs/textures.md; figures in bench/README.md).
//
//   rockbake_texture_bench [PRESET] [--resolution N] [--size S] [--threads N] [--lod-size halved|full]
//                          [--out DIR] [--dump] [--no-fidelity] [--atlas-only] [--normal-map K=FILE]
//
// Bakes PRESET (default presets/goblin.yaml) in-process through the simulation and the mesh
// stage (bakeMeshes, which hands over the bake source: the refined surface before
// simplification). Then, for each rule of the LODs' map sizes (`texture.lod_size`, default
// both): bakes the texture set at 1 and 2 threads (default both; files compared byte for
// byte) into DIR/<rule>/threads<N>, printing each step's wall and CPU seconds and the memory
// the set added (peak RSS during it over RSS before). Per LOD it reports the UV targets
// (texels claimed by two triangles, atlas use, share of the surface within 2x of the median
// texel density) and, unless --no-fidelity, the normal fidelity: the mean angle between LOD0's
// normal and the LOD's, geometry alone and decoded from the written PNGs by glTF's rules in
// this file's own code, and the base colour map's mean absolute difference (linear) from
// LOD0's vertex colours. --dump writes each LOD's atlas, charts in colours, into DIR/<rule>.
// --atlas-only builds each LOD's UV atlas alone, at the map size the rule gives it, and reports
// its charts, the segmentation's and the whole atlas's seconds, and the UV targets.
// --normal-map K=FILE reads LOD K's normal map for the fidelity figures from FILE instead (an RGB
// or RGBA PNG of the map's size: a compressed set's map decoded by `basisu -unpack`, say).
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <malloc.h>
#include <png.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/hash.h"
#include "inputs/resolve_shape.h"
#include "pipeline/bake_meshes.h"
#include "platform/memory.h"
#include "platform/png_image.h"
#include "platform/stopwatch.h"
#include "preset/load_preset.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

#include "texture/rasterize_uv.h"
#include "texture/ray_source.h"
#include "texture/segment_charts.h"
#include "texture/texture_files.h"
#include "texture/texture_set.h"
#include "texture/trace_texels.h"
#include "texture/uv_atlas.h"

namespace rockbake {
namespace {

struct Asset {
  AssetMeshes source;             // the bake source: refined, detailed, coloured, about the pivot
  std::vector<AssetMeshes> lods;  // LOD0, LOD1, …
  double voxel_size = 0;
};

// The mesh stage as the bake runs it (pipeline/bake_meshes.h), with its bake source.
Asset bakeAsset(const Preset& preset) {
  const VoxelRock rock = weatherRock(buildInitialRock(resolveShape(preset), preset), preset).rock;
  MeshStageResult meshes = bakeMeshes(rock, preset, /*keep_bake_source=*/true);
  Asset a;
  a.voxel_size = rock.layout.h;
  a.source = std::move(meshes.bake_source);
  a.lods.push_back(std::move(meshes.meshes));
  for (AssetMeshes& lod : meshes.lods) a.lods.push_back(std::move(lod));
  return a;
}

struct UvFigures {
  double contested = 0, use = 0, within_twice_median = 0;
};

UvFigures uvFigures(const UvAtlas& atlas, const TexelMap& texels) {
  UvFigures f;
  f.contested = double(texels.contested) / double(std::max<std::size_t>(texels.covered, 1));
  f.use = double(texels.covered) / double(texels.texels.size());
  std::vector<std::pair<double, double>> density;
  double total = 0;
  for (const SurfaceMesh* s : {&atlas.meshes.rock, &atlas.meshes.colluvium})
    for (const auto& t : s->triangles) {
      const auto &a = s->positions[t[0]], &b = s->positions[t[1]], &c = s->positions[t[2]];
      const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
      const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const auto &p = s->uvs[t[0]], &q = s->uvs[t[1]], &r = s->uvs[t[2]];
      const double uv_area = 0.5 * std::abs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
      if (area <= 0) continue;
      density.push_back({std::sqrt(uv_area / area), area});
      total += area;
    }
  std::sort(density.begin(), density.end());
  double acc = 0, median = 0;
  for (const auto& [d, a] : density)
    if ((acc += a) >= 0.5 * total) {
      median = d;
      break;
    }
  double within = 0;
  for (const auto& [d, a] : density)
    if (d >= 0.5 * median && d <= 2 * median) within += a;
  f.within_twice_median = within / total;
  return f;
}

// Charts in colours (by the triangle's chart through shared vertices), gutters black.
void dumpAtlas(const UvAtlas& atlas, const TexelMap& texels, const std::filesystem::path& file) {
  std::vector<std::uint32_t> chart;
  std::uint32_t offset = 0;
  for (const SurfaceMesh* m : {&atlas.meshes.rock, &atlas.meshes.colluvium}) {
    std::vector<std::uint32_t> parent(m->positions.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](std::uint32_t v) {
      while (parent[v] != v) v = parent[v] = parent[parent[v]];
      return v;
    };
    for (const auto& t : m->triangles) parent[find(t[1])] = find(t[0]), parent[find(t[2])] = find(t[0]);
    for (const auto& t : m->triangles) chart.push_back(offset + find(t[0]));
    offset += std::uint32_t(m->positions.size());
  }
  RgbImage image;
  image.width = image.height = texels.size;
  image.pixels.assign(texels.texels.size() * 3, 0);
  for (std::size_t i = 0; i < texels.texels.size(); ++i) {
    const std::uint32_t t = texels.texels[i];
    if (t == kEmptyTexel) continue;
    const std::uint64_t h = mix64(chart[t]);
    for (int c = 0; c < 3; ++c) image.pixels[3 * i + c] = std::uint8_t(64 + (h >> (8 * c)) % 192);
  }
  writePngRgb(file, image);
}

// An RGB PNG as written (T: std::uint16_t for 16 bits, std::uint8_t for 8), read with libpng's
// own API (no gamma handling): the bench decodes normal and base colour maps without the
// baker's code.
template <class T>
std::vector<T> readPngRgb(const std::filesystem::path& file, int& size) {
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (!f) throw std::runtime_error("cannot open " + file.string());
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    throw std::runtime_error("cannot read " + file.string());
  }
  png_init_io(png, f);
  // RGB at T's depth whatever the file holds: 8-bit samples widened (× 257) for 16-bit reads (the
  // compact set's normal maps), alpha dropped (a decoded KTX2's RGBA).
  png_read_png(png, info,
               PNG_TRANSFORM_STRIP_ALPHA |
                   (sizeof(T) == 2 ? PNG_TRANSFORM_SWAP_ENDIAN | PNG_TRANSFORM_EXPAND_16 : PNG_TRANSFORM_STRIP_16),
               nullptr);
  if (png_get_channels(png, info) != 3) throw std::runtime_error(file.string() + ": not an RGB image");
  size = int(png_get_image_width(png, info));
  png_bytepp rows = png_get_rows(png, info);
  std::vector<T> pixels(std::size_t(size) * std::size_t(size) * 3);
  for (int y = 0; y < size; ++y)
    std::memcpy(&pixels[std::size_t(y) * std::size_t(size) * 3], rows[y], std::size_t(size) * 3 * sizeof(T));
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  return pixels;
}

// sRGB's transfer function, decoded (IEC 61966-2-1).
double srgbToLinear(std::uint8_t byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

using V = std::array<double, 3>;
V sub(const V& a, const V& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
V cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V unit(const V& a) {
  const double l = std::sqrt(dot(a, a));
  return l > 0 ? V{a[0] / l, a[1] / l, a[2] / l} : a;
}
double angle(const V& a, const V& b) {
  return std::acos(std::clamp(dot(unit(a), unit(b)), -1.0, 1.0)) * 180.0 / 3.14159265358979;
}

struct Fidelity {
  // Mean angle, degrees, between LOD0's normal and the LOD's: geometry alone (interpolated
  // NORMAL), the LOD's map decoded against LOD0's geometry, and both with their maps.
  double geometry = 0, mapped = 0, both_mapped = 0;
};

// A surface's shading at barycentrics w of a triangle: its interpolated NORMAL and, with a map,
// the normal decoded from the map's texel at the interpolated uv by glTF's rules
// (n = normalize(x·T + y·B + z·N), B = cross(N, T)·w, each interpolated and normalised).
struct Shading {
  V geometry, decoded;
};
Shading shade(const SurfaceMesh& m, std::uint32_t triangle, const double w[3], const std::vector<std::uint16_t>& map,
              int size) {
  V n{0, 0, 0}, t{0, 0, 0}, b{0, 0, 0};
  double u = 0, v = 0;
  for (int c = 0; c < 3; ++c) {
    const std::uint32_t i = m.triangles[triangle][c];
    const V vn{m.normals[i][0], m.normals[i][1], m.normals[i][2]};
    const V vt{m.tangents[i][0], m.tangents[i][1], m.tangents[i][2]};
    const V vb = cross(vn, vt);
    for (int k = 0; k < 3; ++k) {
      n[k] += w[c] * vn[k];
      t[k] += w[c] * vt[k];
      b[k] += w[c] * vb[k] * m.tangents[i][3];
    }
    u += w[c] * m.uvs[i][0], v += w[c] * m.uvs[i][1];
  }
  n = unit(n), t = unit(t), b = unit(b);
  const int x = std::clamp(int(u * size), 0, size - 1), y = std::clamp(int(v * size), 0, size - 1);
  const std::uint16_t* texel = &map[(std::size_t(y) * std::size_t(size) + std::size_t(x)) * 3];
  V d;
  for (int k = 0; k < 3; ++k) d[k] = texel[k] / 65535.0 * 2.0 - 1.0;
  V decoded;
  for (int k = 0; k < 3; ++k) decoded[k] = d[0] * t[k] + d[1] * b[k] + d[2] * n[k];
  return {n, unit(decoded)};
}

// Over LOD k's covered texels, against LOD0 where the line along LOD k's normal meets it.
Fidelity fidelity(const AssetMeshes& lod, const std::vector<std::uint16_t>& map, int size, const AssetMeshes& lod0,
                  const std::vector<std::uint16_t>& lod0_map, int lod0_size, const RaySource& lod0_rays, double reach) {
  const TexelMap texels = rasterizeUv(lod, size);
  Fidelity sum;
  std::size_t count = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
      if (texels.texels[i] == kEmptyTexel) continue;
      const TriangleRef ref = triangleRef(lod, texels.texels[i]);
      const SurfaceMesh& m = ref.surface == 0 ? lod.rock : lod.colluvium;
      const auto w = texelBarycentrics(m, ref.triangle, x, y, size);
      const double weights[3] = {w[0], w[1], w[2]};
      const Shading here = shade(m, ref.triangle, weights, map, size);
      V p{0, 0, 0};
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) p[k] += w[c] * m.positions[m.triangles[ref.triangle][c]][k];
      const V& n = here.geometry;
      const SourceHit hit = lod0_rays.nearestAlong(ref.surface, {float(p[0]), float(p[1]), float(p[2])},
                                                   {float(n[0]), float(n[1]), float(n[2])}, float(reach));
      if (!hit.hit) continue;
      const double w0[3] = {1.0 - hit.u - hit.v, hit.u, hit.v};
      const Shading there = shade(ref.surface == 0 ? lod0.rock : lod0.colluvium, hit.triangle, w0, lod0_map, lod0_size);
      sum.geometry += angle(here.geometry, there.geometry);
      sum.mapped += angle(here.decoded, there.geometry);
      sum.both_mapped += angle(here.decoded, there.decoded);
      ++count;
    }
  const double n = double(std::max<std::size_t>(count, 1));
  return {sum.geometry / n, sum.mapped / n, sum.both_mapped / n};
}

// The mean absolute difference, linear RGB averaged over the channels and the LOD's covered
// texels, between the LOD's base colour map (decoded from the PNG by sRGB's rule) and LOD0's
// interpolated vertex colours where the line along the LOD's normal meets LOD0.
double baseColourError(const AssetMeshes& lod, const std::vector<std::uint8_t>& map, int size, const AssetMeshes& lod0,
                       const RaySource& lod0_rays, double reach) {
  const TexelMap texels = rasterizeUv(lod, size);
  double sum = 0;
  std::size_t count = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
      if (texels.texels[i] == kEmptyTexel) continue;
      const TriangleRef ref = triangleRef(lod, texels.texels[i]);
      const SurfaceMesh& m = ref.surface == 0 ? lod.rock : lod.colluvium;
      const auto w = texelBarycentrics(m, ref.triangle, x, y, size);
      V p{0, 0, 0}, n{0, 0, 0};
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t v = m.triangles[ref.triangle][c];
          p[k] += w[c] * m.positions[v][k], n[k] += w[c] * m.normals[v][k];
        }
      n = unit(n);
      const SourceHit hit = lod0_rays.nearestAlong(ref.surface, {float(p[0]), float(p[1]), float(p[2])},
                                                   {float(n[0]), float(n[1]), float(n[2])}, float(reach));
      if (!hit.hit) continue;
      const SurfaceMesh& m0 = ref.surface == 0 ? lod0.rock : lod0.colluvium;
      const double w0[3] = {1.0 - hit.u - hit.v, hit.u, hit.v};
      for (int k = 0; k < 3; ++k) {
        double expected = 0;
        for (int c = 0; c < 3; ++c) expected += w0[c] * m0.colors[m0.triangles[hit.triangle][c]][k];
        sum += std::abs(srgbToLinear(map[3 * i + std::size_t(k)]) - expected);
      }
      ++count;
    }
  return sum / double(3 * std::max<std::size_t>(count, 1));
}

// A /proc/self/status field in MiB ("VmRSS", "VmHWM").
double statusMiB(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(std::string(field) + ":", 0) == 0) return std::stod(line.substr(std::strlen(field) + 1)) / 1024.0;
  return 0.0;
}

// Starts the peak-memory count afresh (Linux: clear_refs 5 resets VmHWM to the current RSS).
void resetPeakMemory() {
  std::ofstream("/proc/self/clear_refs") << "5";
}

// User and system CPU seconds of the whole process so far (all threads).
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string readAll(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Each LOD's atlas alone (--atlas-only): charts, seconds (segmentation, then the whole atlas
// with it), the UV targets.
void atlasOnly(const Asset& asset, const TextureParams& params, const std::filesystem::path& out, bool dump) {
  for (std::size_t k = 0; k < asset.lods.size(); ++k) {
    const int size = lodMapSize(params, int(k));
    Stopwatch clock;
    std::size_t charts = 0;
    for (const SurfaceMesh* m : {&asset.lods[k].rock, &asset.lods[k].colluvium}) {
      const std::vector<std::uint32_t> chart = segmentCharts(*m);
      if (!chart.empty()) charts += *std::max_element(chart.begin(), chart.end()) + 1;
    }
    const double segmentation = clock.lap();
    const double cpu0 = cpuSeconds();
    const UvAtlas atlas = buildUvAtlas(asset.lods[k], size, params.padding);
    const double whole = clock.lap(), cpu = cpuSeconds() - cpu0;
    const TexelMap texels = rasterizeUv(atlas.meshes, size);
    const UvFigures f = uvFigures(atlas, texels);
    std::printf(
        "LOD%zu at %d: %zu segments, %zu charts; segmentation %.3f s, atlas %.3f s (CPU %.3f s); contested %.3f %%, "
        "use %.1f %%, within 2x of median density %.1f %%\n",
        k, size, charts, atlas.charts, segmentation, whole, cpu, 100 * f.contested, 100 * f.use,
        100 * f.within_twice_median);
    if (dump) {
      std::filesystem::create_directories(out);
      dumpAtlas(atlas, texels, out / ("atlas_lod" + std::to_string(k) + ".png"));
    }
  }
}

}  // namespace
}  // namespace rockbake

int main(int argc, char** argv) {
  rockbake::returnLargeBlocksToTheSystem();  // as the command line does
  using namespace rockbake;
  std::filesystem::path preset_file = std::filesystem::path(ROCKBAKE_SOURCE_DIR) / "presets" / "goblin.yaml";
  std::optional<int> resolution;
  int size = 2048;
  std::filesystem::path out = std::filesystem::temp_directory_path() / "rockbake-texture-bench";
  bool dump = false;
  std::vector<int> thread_counts{1, 2};
  std::vector<std::string> rules{"halved", "full"};
  bool fidelity_figures = true;
  bool atlas_only = false;
  std::map<std::size_t, std::filesystem::path> normal_maps;  // --normal-map K=FILE
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
    if (a == "--resolution")
      resolution = std::stoi(next());
    else if (a == "--size")
      size = std::stoi(next());
    else if (a == "--out")
      out = next();
    else if (a == "--dump")
      dump = true;
    else if (a == "--threads")
      thread_counts = {std::stoi(next())};
    else if (a == "--no-fidelity")
      fidelity_figures = false;
    else if (a == "--atlas-only")
      atlas_only = true;
    else if (a == "--lod-size")
      rules = {next()};
    else if (a == "--normal-map") {
      const std::string v = next();
      const std::size_t eq = v.find('=');
      if (eq == std::string::npos) throw std::invalid_argument("--normal-map: expected K=FILE, found " + v);
      normal_maps[std::stoul(v.substr(0, eq))] = v.substr(eq + 1);
    } else
      preset_file = a;
  }
  spdlog::set_level(spdlog::level::warn);
  const Preset preset = loadPreset(preset_file, {{}, {}, resolution});
  Stopwatch clock;
  const Asset asset = bakeAsset(preset);
  std::printf(
      "%s at %d: bake source %zu + %zu triangles, LODs %s; %.2f s to bake\n", preset.name.c_str(),
      preset.grid.resolution, asset.source.rock.triangles.size(), asset.source.colluvium.triangles.size(),
      [&] {
        std::string l;
        for (const AssetMeshes& m : asset.lods)
          l += std::to_string(m.rock.triangles.size() + m.colluvium.triangles.size()) + " ";
        return l;
      }()
          .c_str(),
      clock.lap());
  if (atlas_only) {
    for (const std::string& rule : rules) {
      std::printf("\n== lod_size: %s ==\n", rule.c_str());
      TextureParams params;
      params.size = size;
      params.lod_size = rule == "full" ? LodMapSize::Full : LodMapSize::Halved;
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(thread_counts.back()));
      atlasOnly(asset, params, out / rule, dump);
    }
    return 0;
  }
  const double bake_peak = statusMiB("VmHWM");
  {
    malloc_trim(0);
    const double before = statusMiB("VmRSS");
    const RaySource scene(asset.source);
    std::printf("memory: the bake peaked at %.0f MiB; the source's ray scene alone takes %.0f MiB\n", bake_peak,
                statusMiB("VmRSS") - before);
  }
  TextureSetRequest request;
  request.params.size = size;
  request.seed = preset.seed;
  request.voxel_size = asset.voxel_size;
  request.name = preset.name;

  for (const std::string& rule : rules) {
    std::printf("\n== lod_size: %s ==\n", rule.c_str());
    request.params.lod_size = rule == "full" ? LodMapSize::Full : LodMapSize::Halved;
    std::vector<TextureSet> sets;
    for (int threads : thread_counts) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      request.folder = out / rule / ("threads" + std::to_string(threads));
      malloc_trim(0);  // what the bake freed goes back to the system: the figure counts live memory
      const double rss0 = statusMiB("VmRSS");
      resetPeakMemory();
      clock.lap();
      const double cpu0 = cpuSeconds();
      sets.push_back(bakeTextureSet(asset.lods, asset.source, request));
      const double total = clock.lap(), cpu = cpuSeconds() - cpu0;
      std::printf(
          "memory: %.0f MiB live before the texture set, peak %.0f MiB during it (+%.0f MiB); the whole "
          "run's peak %.0f MiB over the bake's %.0f MiB\n",
          rss0, statusMiB("VmHWM"), statusMiB("VmHWM") - rss0, std::max(bake_peak, statusMiB("VmHWM")), bake_peak);
      std::uintmax_t bytes = 0;
      for (const TextureFile& f : sets.back().files) bytes += std::filesystem::file_size(request.folder / f.file);
      std::printf("%d thread(s): textures %.2f s in all (%.2f s of CPU), %zu files, %.1f MB, %zu texels missed\n",
                  threads, total, cpu, sets.back().files.size(), 1e-6 * double(bytes), sets.back().missed);
      for (const PhaseTime& step : sets.back().steps.all())
        std::printf("  %-18s %7.3f s (CPU %.3f s)\n", step.name.c_str(), step.seconds, step.cpu_seconds);
    }
    if (sets.size() == 2) {
      bool same = true;
      for (const TextureFile& f : sets[0].files)
        same &= readAll(out / rule / "threads1" / f.file) == readAll(out / rule / "threads2" / f.file);
      std::printf("files at 1 and 2 threads: %s\n", same ? "byte-identical" : "DIFFERENT");
    }
    const TextureSet& set = sets.back();
    const std::filesystem::path last = out / rule / ("threads" + std::to_string(thread_counts.back()));
    const RaySource lod0_rays(set.lods[0]);
    int lod0_size = 0;
    const auto lod0_map =
        readPngRgb<std::uint16_t>(last / textureFileName(preset.name, TextureMap::Normal, 0), lod0_size);
    for (std::size_t k = 0; k < set.lods.size(); ++k) {
      const TexelMap texels = rasterizeUv(set.lods[k], set.sizes[k]);
      UvAtlas atlas;
      atlas.meshes = set.lods[k];
      const UvFigures f = uvFigures(atlas, texels);
      int map_size = 0;
      const auto map = readPngRgb<std::uint16_t>(
          normal_maps.count(k) ? normal_maps.at(k) : last / textureFileName(preset.name, TextureMap::Normal, int(k)),
          map_size);
      if (normal_maps.count(k)) std::printf("LOD%zu's normal map read from %s\n", k, normal_maps.at(k).c_str());
      int colour_size = 0;
      const auto colour = readPngRgb<std::uint8_t>(
          last / textureFileName(preset.name, TextureMap::BaseColor, k == 0 ? -1 : int(k)), colour_size);
      const double colour_error =
          baseColourError(set.lods[k], colour, colour_size, set.lods[0], lod0_rays, 0.1 * lod0_rays.radius());
      const Fidelity fid = fidelity_figures ? fidelity(set.lods[k], map, map_size, set.lods[0], lod0_map, lod0_size,
                                                       lod0_rays, 0.1 * lod0_rays.radius())
                                            : Fidelity{};
      std::printf(
          "LOD%zu: %zu triangles (target %s), %.0f texels/unit; contested %.3f %%, use %.1f %%, within 2x of "
          "median density %.1f %%; normal vs LOD0: geometry %.2f°, map %.2f° (%.2f x), both with maps %.2f° "
          "(%.2f x); base colour vs LOD0's vertex colours %.4f (linear, mean absolute)\n",
          k, set.lods[k].rock.triangles.size() + set.lods[k].colluvium.triangles.size(),
          k == 0 ? "-" : std::to_string(int(preset.mesh.lods[k - 1])).c_str(), set.texels_per_unit[k],
          100 * f.contested, 100 * f.use, 100 * f.within_twice_median, fid.geometry, fid.mapped,
          fid.mapped / std::max(fid.geometry, 1e-9), fid.both_mapped, fid.both_mapped / std::max(fid.geometry, 1e-9),
          colour_error);
      if (dump) dumpAtlas(atlas, texels, out / rule / ("atlas_lod" + std::to_string(k) + ".png"));
    }
  }
  return 0;
}
