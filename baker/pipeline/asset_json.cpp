#include "pipeline/asset_json.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/colour.h"

namespace rockbake {

std::array<double, 3> averageColor(const AssetMeshes& meshes) {
  std::array<double, 3> sum{};
  double area = 0;
  for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium}) {
    if (m->colors.size() != m->positions.size()) continue;
    for (const auto& t : m->triangles) {
      const auto& a = m->positions[t[0]];
      const auto& b = m->positions[t[1]];
      const auto& c = m->positions[t[2]];
      const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
      const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
      const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
      const double w = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
      for (int k = 0; k < 3; ++k)
        for (int ch = 0; ch < 3; ++ch) sum[ch] += w / 3.0 * m->colors[t[k]][ch];
      area += w;
    }
  }
  if (area <= 0) return {0, 0, 0};
  return {sum[0] / area, sum[1] / area, sum[2] / area};
}

nlohmann::ordered_json assetJson(const AssetDescription& asset) {
  if (asset.lods.empty() || !asset.lods.front().meshes) throw std::invalid_argument("asset.json needs LOD0");
  const AssetMeshes& lod0 = *asset.lods.front().meshes;
  nlohmann::ordered_json j;
  j["rockbake_asset"] = 1;
  j["name"] = asset.name;
  j["tags"] = asset.tags;
  j["units_per_meter"] = asset.units_per_meter;
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
    lods.push_back({{"level", i},
                    {"file", asset.lods[i].file},
                    {"triangles", m.rock.triangles.size() + m.colluvium.triangles.size()},
                    {"vertices", m.rock.positions.size() + m.colluvium.positions.size()}});
  }
  j["lods"] = lods;
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
  j["input_hash"] = asset.input_hash;
  return j;
}

void writeAssetJson(const AssetDescription& asset, const std::filesystem::path& asset_dir) {
  writeFileAtomically(asset_dir / kAssetFile, assetJson(asset).dump(2) + "\n");
}

}  // namespace rockbake
