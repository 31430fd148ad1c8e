#include "pipeline/asset_json.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "geometry/triangle_geometry.h"
#include "mesh/extract_surfaces.h"
#include "platform/atomic_file.h"
#include "platform/colour.h"
#include "texture/pack_charts.h"

namespace rockbake {

std::array<double, 3> averageColor(const AssetMeshes& meshes) {
  std::array<double, 3> sum{};
  double area = 0;
  for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium}) {
    if (m->colors.size() != m->positions.size()) continue;
    for (const auto& t : m->triangles) {
      const double w = triangleArea(m->positions[t[0]], m->positions[t[1]], m->positions[t[2]]);
      for (int k = 0; k < 3; ++k)
        for (int ch = 0; ch < 3; ++ch) sum[ch] += w / 3.0 * m->colors[t[k]][ch];
      area += w;
    }
  }
  if (area <= 0) return {0, 0, 0};
  return {sum[0] / area, sum[1] / area, sum[2] / area};
}

namespace {

// Volumes in cubic metres, to the cubic millimetre.
nlohmann::ordered_json collisionJson(const AssetCollision& collision, double units_per_meter) {
  nlohmann::ordered_json hulls = nlohmann::ordered_json::array();
  std::size_t vertices = 0;
  const double units3_per_m3 = units_per_meter * units_per_meter * units_per_meter;
  for (const AssetHull& h : collision.hulls) {
    hulls.push_back(
        {{"node", h.node}, {"vertices", h.vertices}, {"volume_m3", std::round(1e9 * h.volume / units3_per_m3) / 1e9}});
    vertices += h.vertices;
  }
  return {{"file", collision.file},
          {"naming", collision.naming},
          {"hull_count", collision.hulls.size()},
          {"vertex_count", vertices},
          {"hulls", hulls}};
}

}  // namespace

namespace {

double rounded(double v) {
  return std::round(v * 1e6) / 1e6;
}

}  // namespace

nlohmann::ordered_json groundJson(const VoxelRock& rock, const std::array<double, 3>& pivot, double sink,
                                  double units_per_meter) {
  const GridLayout& g = rock.layout;
  if (!g.ground) return nullptr;
  const int layer = std::clamp(int(std::floor(sink / g.h)), 0, g.nz - 1);
  std::vector<std::array<double, 2>> all, own;
  std::size_t cells = 0;
  for (int y = 0; y < g.ny; ++y)
    for (int x = 0; x < g.nx; ++x) {
      const Material m = rock.material[g.index(x, y, layer)];
      if (m == Material::Air) continue;
      ++cells;
      for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {0, 1}, {1, 1}}) {
        const std::array<double, 2> corner{g.origin[0] + (x + dx) * g.h - pivot[0],
                                           g.origin[1] + (y + dy) * g.h - pivot[1]};
        all.push_back(corner);
        if (m == Material::Rock) own.push_back(corner);
      }
    }
  const auto metres = [&](const std::vector<std::array<double, 2>>& points) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const auto& p : convexHull(points))
      list.push_back({rounded(p[0] / units_per_meter), rounded(p[1] / units_per_meter)});
    return list;
  };
  return {{"pivot", "ground-contact"},
          {"sink_m", rounded(sink / units_per_meter)},
          {"suggested_burial_m", rounded(suggestedBurialDepth(rock) / units_per_meter)},
          {"footprint_m", metres(all)},
          {"rock_footprint_m", metres(own)},
          {"contact_area_m2", rounded(double(cells) * g.h * g.h / (units_per_meter * units_per_meter))}};
}

nlohmann::ordered_json clastsJson(const ClastSet& set, double h, double units_per_meter) {
  if (set.stones.empty()) return nullptr;
  nlohmann::ordered_json lods = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < set.lod_counts.size(); ++k)
    lods.push_back({{"level", k}, {"stones", set.lod_counts[k]}, {"triangles", clastTriangles(set, k)}});
  nlohmann::ordered_json maps = nlohmann::ordered_json::array();
  for (const auto& [type, file] : {std::pair{"base_color", set.base_color}, {"normal", set.normal}, {"orm", set.orm}})
    if (!file.empty())
      maps.push_back({{"type", type}, {"file", std::string("textures/") + file}, {"size", set.map_size}});
  return {{"stones", set.stones.size()},
          {"shapes", set.shapes.size()},
          {"voxel_size_m", h / units_per_meter},
          {"size_m", {set.stones.back().scale / units_per_meter, set.stones.front().scale / units_per_meter}},
          {"lods", lods},
          {"maps", maps}};
}

nlohmann::ordered_json assetJson(const AssetDescription& asset) {
  if (asset.lods.empty() || !asset.lods.front().meshes) throw std::invalid_argument("asset.json needs LOD0");
  const AssetMeshes& lod0 = *asset.lods.front().meshes;
  nlohmann::ordered_json j;
  j["rockbake_asset"] = 1;
  j["name"] = asset.name;
  j["tags"] = asset.tags;
  j["units_per_meter"] = asset.units_per_meter;
  if (!asset.delivery.is_null()) j["delivery"] = asset.delivery;
  // The size of what ships: LOD0's own vertices.
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const SurfaceMesh* m : {&lod0.rock, &lod0.colluvium})
    for (const auto& p : m->positions)
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double(p[a])), hi[a] = std::max(hi[a], double(p[a]));
  nlohmann::ordered_json size = nlohmann::ordered_json::array();
  for (int a = 0; a < 3; ++a)
    size.push_back(hi[a] >= lo[a] ? std::round(1e6 * (hi[a] - lo[a]) / asset.units_per_meter) / 1e6 : 0.0);
  j["size_m"] = size;
  j["pivot"] = "footprint-centre-on-ground";
  j["up_axis"] = {{"glb", "y"}, {"obj", "y"}, {"ply", "z"}, {"vdb", "z"}};
  nlohmann::ordered_json lods = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < asset.lods.size(); ++i) {
    const AssetMeshes& m = *asset.lods[i].meshes;
    nlohmann::ordered_json lod = {{"level", i},
                                  {"file", asset.lods[i].file},
                                  {"triangles", m.rock.triangles.size() + m.colluvium.triangles.size()},
                                  {"vertices", m.rock.positions.size() + m.colluvium.positions.size()}};
    if (asset.lods[i].map_size > 0) {
      lod["map_size"] = asset.lods[i].map_size;
      // Pixels per metre, as a Megascans payload gives it: texels per world unit times world units per metre.
      lod["texel_density"] = std::round(10 * asset.lods[i].texels_per_unit * asset.units_per_meter) / 10;
    }
    lods.push_back(lod);
  }
  j["lods"] = lods;
  if (!asset.maps.empty()) {
    nlohmann::ordered_json maps = nlohmann::ordered_json::array();
    for (const AssetMap& m : asset.maps)
      maps.push_back({{"type", m.type},
                      {"lod", m.lod},
                      {"file", m.file},
                      {"size", {m.size, m.size}},
                      {"colour_space", m.colour_space},
                      {"channels", m.channels},
                      {"bits", m.bits}});
    j["maps"] = maps;
  }
  const std::array<double, 3> linear = averageColor(lod0);
  const auto byte = [](double c) {
    return int(std::lround(std::clamp(double(linearToSrgb(float(c))), 0.0, 1.0) * 255));
  };
  j["average_color"] = {
      {"srgb", fmt::format("#{:02x}{:02x}{:02x}", byte(linear[0]), byte(linear[1]), byte(linear[2]))},
      {"linear",
       {std::round(1e4 * linear[0]) / 1e4, std::round(1e4 * linear[1]) / 1e4, std::round(1e4 * linear[2]) / 1e4}}};
  j["preview"] = asset.preview.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(asset.preview);
  j["movie"] = asset.movie.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(asset.movie);
  if (asset.collision) j["collision"] = collisionJson(*asset.collision, asset.units_per_meter);
  if (!asset.clasts.is_null()) j["clasts"] = asset.clasts;
  if (!asset.ground.is_null()) j["ground"] = asset.ground;
  if (!asset.sets.is_null()) j["sets"] = asset.sets;
  if (!asset.individual.is_null()) j["individual"] = asset.individual;
  j["input_hash"] = asset.input_hash;
  return j;
}

void writeAssetJson(const AssetDescription& asset, const std::filesystem::path& asset_dir) {
  writeFileAtomically(asset_dir / kAssetFile, assetJson(asset).dump(2) + "\n");
}

}  // namespace rockbake
