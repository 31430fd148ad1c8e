#include "texture/uv_atlas.h"

#include "geometry/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/vec3.h"
#include "geometry/disjoint_set.h"
#include "geometry/edge_table.h"
#include "texture/pack_charts.h"
#include "texture/parameterize_chart.h"
#include "texture/segment_charts.h"

namespace rockbake {
namespace {

struct FlatChart {
  int surface = 0;
  std::vector<std::uint32_t> triangles;  // ascending
  ChartUv uv;
};

constexpr std::size_t kMergeTries = 2;
constexpr std::uint32_t kNoChart = 0xffffffffu;

// Two charts as they stand: (a, b, a's version, b's version), a < b. A chart's version counts
// the merges into it, so a union named so is of the same triangles until either changes.
using ChartUnion = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;
// A union's triangles (ascending) and its flattening.
using FlatUnion = std::pair<std::vector<std::uint32_t>, ChartUv>;

// What mergeFlattenedCharts keeps as it merges: the chart that owns each triangle, each chart's area,
// its hull's area in the plane and its version, and the unions that failed.
class ChartMerger {
 public:
  ChartMerger(const SurfaceMesh& mesh, const EdgeTable& edges, std::vector<FlatChart>& charts,
              const std::vector<std::uint8_t>& hidden)
      : mesh_(mesh),
        edges_(edges),
        charts_(charts),
        hidden_(hidden),
        owner_(mesh.triangles.size(), kNoChart),
        area_(charts.size(), 0.0),
        hull_(charts.size(), 0.0),
        version_(charts.size(), 0) {
    for (std::uint32_t c = 0; c < charts.size(); ++c) {
      for (std::uint32_t t : charts[c].triangles) {
        const auto& tri = mesh.triangles[t];
        const Vec3d a = toVec3d(mesh.positions[tri[0]]), b = toVec3d(mesh.positions[tri[1]]),
                    d = toVec3d(mesh.positions[tri[2]]);
        owner_[t] = c;
        area_[c] += 0.5 * length(cross(sub(b, a), sub(d, a)));
      }
      hull_[c] = convexHullArea(charts[c].uv.uv);
    }
  }

  // The charts in the order they are tried: smallest area first.
  std::vector<std::uint32_t> smallestFirst() const {
    std::vector<std::uint32_t> order(charts_.size());
    for (std::uint32_t c = 0; c < order.size(); ++c) order[c] = c;
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return area_[a] < area_[b]; });
    return order;
  }

  // The flattenings of the unions that the charts order[from, from + count) would try, as
  // things stand, made side by side.
  std::map<ChartUnion, FlatUnion> flattenAhead(const std::vector<std::uint32_t>& order, std::size_t from,
                                               std::size_t count) const {
    std::vector<ChartUnion> unions;
    for (std::size_t k = from; k < std::min(order.size(), from + count); ++k) {
      const std::uint32_t c = order[k];
      if (charts_[c].triangles.empty()) continue;
      for (std::uint32_t b : neighbours(c))
        if (const ChartUnion u = unionOf(c, b);
            !failed_.count(u) && std::find(unions.begin(), unions.end(), u) == unions.end())
          unions.push_back(u);
    }
    std::vector<FlatUnion> made(unions.size());
    tbb::parallel_for(std::size_t(0), unions.size(),
                      [&](std::size_t i) { made[i] = flattenUnion(std::get<0>(unions[i]), std::get<1>(unions[i])); });
    std::map<ChartUnion, FlatUnion> ahead;
    for (std::size_t i = 0; i < unions.size(); ++i) ahead.emplace(unions[i], std::move(made[i]));
    return ahead;
  }

  // Merges chart c into the first of its neighbours whose union flattens and packs no worse,
  // if any; `ahead`'s flattening of a union is used where it has one.
  void tryMerges(std::uint32_t c, std::map<ChartUnion, FlatUnion>& ahead) {
    if (charts_[c].triangles.empty()) return;
    for (const std::uint32_t b : neighbours(c)) {
      // A union tried before, of the same two charts unchanged since, would fail again.
      const ChartUnion tried = unionOf(c, b);
      if (failed_.count(tried)) continue;
      const auto made = ahead.find(tried);
      auto [both, flat] = made != ahead.end() ? std::move(made->second) : flattenUnion(c, b);
      const double merged_hull = flat.status == ChartStatus::Ok ? convexHullArea(flat.uv) : 0.0;
      if (flat.status != ChartStatus::Ok || merged_hull > hull_[c] + hull_[b]) {
        failed_.insert(tried);
        continue;
      }
      for (std::uint32_t t : charts_[c].triangles) owner_[t] = b;
      charts_[b].triangles = std::move(both);
      charts_[b].uv = std::move(flat);
      charts_[c].triangles.clear();
      area_[b] += area_[c];
      hull_[b] = merged_hull;
      ++version_[b];
      break;
    }
  }

 private:
  ChartUnion unionOf(std::uint32_t a, std::uint32_t b) const {
    return a < b ? ChartUnion{a, b, version_[a], version_[b]} : ChartUnion{b, a, version_[b], version_[a]};
  }

  // The neighbours chart c tries, longest shared border first.
  std::vector<std::uint32_t> neighbours(std::uint32_t c) const {
    std::vector<std::pair<double, std::uint32_t>> shared;  // (border length, neighbour)
    for (std::uint32_t t : charts_[c].triangles)
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t u = edges_.faceAcross(3 * t + k);
        if (u == EdgeTable::kNone || owner_[u] == c || owner_[u] == kNoChart) continue;
        if (!hidden_.empty() && hidden_[u] != hidden_[t]) continue;  // hidden and seen surface stay apart
        const auto& tri = mesh_.triangles[t];
        const double l = length(sub(toVec3d(mesh_.positions[tri[(k + 1) % 3]]), toVec3d(mesh_.positions[tri[k]])));
        const auto it =
            std::find_if(shared.begin(), shared.end(), [&](const auto& p) { return p.second == owner_[u]; });
        if (it == shared.end())
          shared.push_back({l, owner_[u]});
        else
          it->first += l;
      }
    std::stable_sort(shared.begin(), shared.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::uint32_t> tries;
    for (std::size_t i = 0; i < shared.size() && i < kMergeTries; ++i) tries.push_back(shared[i].second);
    return tries;
  }

  FlatUnion flattenUnion(std::uint32_t a, std::uint32_t b) const {
    std::vector<std::uint32_t> both;
    std::merge(charts_[a].triangles.begin(), charts_[a].triangles.end(), charts_[b].triangles.begin(),
               charts_[b].triangles.end(), std::back_inserter(both));
    return std::make_pair(std::move(both), parameterizeChart(mesh_, both));
  }

  const SurfaceMesh& mesh_;
  const EdgeTable& edges_;
  std::vector<FlatChart>& charts_;
  const std::vector<std::uint8_t>& hidden_;  // per triangle, or empty
  std::vector<std::uint32_t> owner_;         // per triangle: its chart, or kNoChart
  std::vector<double> area_, hull_;          // per chart
  std::vector<std::uint32_t> version_;       // per chart
  std::set<ChartUnion> failed_;
};

// Merges flattened charts into a neighbour where the union still flattens (parameterizeChart
// accepts it) and packs no worse: its convex hull in the plane is no larger than the two
// charts' hulls together. The border they shared stops costing gutter texels on both sides,
// and the halves of a chart split because it failed come back together where they can.
// Smallest chart first, each tried against the kMergeTries neighbours it shares the longest
// border with (docs/textures.md §1).
// `hidden` (per triangle, or empty): charts never merge across its boundary.
void mergeFlattenedCharts(const SurfaceMesh& mesh, const EdgeTable& edges, std::vector<FlatChart>& charts,
                          const std::vector<std::uint8_t>& hidden) {
  if (charts.size() < 2) return;
  ChartMerger merger(mesh, edges, charts, hidden);
  const std::vector<std::uint32_t> order = merger.smallestFirst();
  // The tries are made in order, one after another, since each merge changes what later charts
  // meet. Their flattenings, nearly all of a try's time, are made ahead, side by side, for the
  // next kAhead charts as things stand; a union's flattening depends on its two charts' triangles
  // alone, named by the charts and their versions, so one made ahead is used only while both are
  // unchanged, and is then exactly what the try would make. The result does not depend on the
  // thread count.
  constexpr std::size_t kAhead = 32;
  std::map<ChartUnion, FlatUnion> ahead;
  for (std::size_t at = 0; at < order.size(); ++at) {
    if (at % kAhead == 0) ahead = merger.flattenAhead(order, at, kAhead);
    merger.tryMerges(order[at], ahead);
  }
  charts.erase(std::remove_if(charts.begin(), charts.end(), [](const FlatChart& c) { return c.triangles.empty(); }),
               charts.end());
}

// Segments and flattens one surface; failing charts are split and flattened again, round by
// round (each round in parallel, results in chart order).
// `hidden` (per triangle, or empty): each chart is cut along its boundary, and the pieces of
// hidden surface are never merged with seen ones, so that they can be packed small.
std::vector<FlatChart> flattenSurface(const SurfaceMesh& mesh, int surface, const std::vector<std::uint8_t>& hidden) {
  std::vector<std::uint32_t> chart_of = segmentCharts(mesh);
  const EdgeTable edges(mesh.triangles);
  if (!hidden.empty()) {
    // The connected pieces of each chart's hidden and seen triangles, numbered in order of first triangle.
    DisjointSet pieces(chart_of.size());
    for (std::uint32_t t = 0; t < chart_of.size(); ++t)
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t u = edges.faceAcross(3 * t + k);
        if (u != EdgeTable::kNone && chart_of[u] == chart_of[t] && hidden[u] == hidden[t]) pieces.unite(t, u);
      }
    chart_of = pieces.labels();
  }
  std::uint32_t count = 0;
  for (std::uint32_t c : chart_of) count = std::max(count, c + 1);
  std::vector<std::vector<std::uint32_t>> pending(count);
  for (std::uint32_t t = 0; t < chart_of.size(); ++t) pending[chart_of[t]].push_back(t);

  std::vector<FlatChart> done;
  while (!pending.empty()) {
    std::vector<ChartUv> flat(pending.size());
    tbb::parallel_for(std::size_t(0), pending.size(),
                      [&](std::size_t i) { flat[i] = parameterizeChart(mesh, pending[i]); });
    std::vector<std::vector<std::uint32_t>> again;
    for (std::size_t i = 0; i < pending.size(); ++i) {
      if (flat[i].status == ChartStatus::Ok) {
        done.push_back({surface, std::move(pending[i]), std::move(flat[i])});
      } else {
        auto halves = splitChart(mesh, edges, pending[i]);
        for (auto& half : halves) {
          std::sort(half.begin(), half.end());
          if (!half.empty()) again.push_back(std::move(half));
        }
      }
    }
    pending = std::move(again);
  }
  mergeFlattenedCharts(mesh, edges, done, hidden);
  // Charts in order of their lowest triangle, whatever round finished them.
  std::sort(done.begin(), done.end(),
            [](const FlatChart& a, const FlatChart& b) { return a.triangles.front() < b.triangles.front(); });
  return done;
}

// The surface with a vertex per chart vertex, numbered in order of first use over the
// triangles, every per-vertex array carried. To be replaced by the mesh kernel's vertex remap.
SurfaceMesh splitAlongSeams(const SurfaceMesh& mesh, const std::vector<const FlatChart*>& charts,
                            const std::vector<std::vector<std::array<double, 2>>>& atlas_uv,
                            const std::vector<std::size_t>& chart_index, std::vector<std::uint32_t>& source) {
  const std::size_t nt = mesh.triangles.size();
  // Per triangle: its chart and its position in the chart's triangle list.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> place(nt);
  for (std::size_t c = 0; c < charts.size(); ++c)
    for (std::uint32_t i = 0; i < charts[c]->triangles.size(); ++i)
      place[charts[c]->triangles[i]] = {std::uint32_t(c), i};
  SurfaceMesh out;
  out.name = mesh.name;
  out.triangles.resize(nt);
  std::unordered_map<std::uint64_t, std::uint32_t> copy;  // (chart, chart vertex) → new vertex
  copy.reserve(2 * mesh.positions.size());
  source.clear();  // new vertex → old
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const auto [c, i] = place[t];
      const ChartUv& flat = charts[c]->uv;
      const std::uint32_t local = flat.corners[i][k];
      const auto [it, fresh] = copy.try_emplace(std::uint64_t(c) << 32 | local, std::uint32_t(source.size()));
      if (fresh) {
        source.push_back(flat.vertices[local]);
        const auto& uv = atlas_uv[chart_index[c]][local];
        out.uvs.push_back({float(uv[0]), float(uv[1])});
      }
      out.triangles[t][k] = it->second;
    }
  const auto carry = [&](const auto& from, auto& to) {
    if (from.size() != mesh.positions.size()) return;
    to.resize(source.size());
    for (std::size_t i = 0; i < source.size(); ++i) to[i] = from[source[i]];
  };
  // Every per-vertex array but the atlas's own (uvs, made above; tangents, made from them later).
  std::apply(
      [&](const auto&... array) {
        ((std::string_view(array.name) == "uvs" || std::string_view(array.name) == "tangents"
              ? void()
              : carry(mesh.*(array.member), out.*(array.member))),
         ...);
      },
      kVertexArrays);
  return out;
}

}  // namespace

UvAtlas buildUvAtlas(const AssetMeshes& meshes, int size, int padding, const HiddenTriangles* hidden_triangles) {
  if (size < 1 || size > 8192 || padding < 0 || padding > 64)
    throw std::invalid_argument("buildUvAtlas: a " + std::to_string(size) + "² map with " + std::to_string(padding) +
                                "-texel gutters is outside 1 … 8192 texels and 0 … 64 texels");
  const std::array<const SurfaceMesh*, 2> surfaces{&meshes.rock, &meshes.colluvium};
  std::array<std::vector<FlatChart>, 2> flat;
  // The surfaces are independent: each one's serial steps (segmentation, merging) overlap the other's.
  const std::vector<std::uint8_t> none;
  const auto hiddenOf = [&](int s) -> const std::vector<std::uint8_t>& {
    return hidden_triangles && (*hidden_triangles)[std::size_t(s)].size() == surfaces[std::size_t(s)]->triangles.size()
               ? (*hidden_triangles)[std::size_t(s)]
               : none;
  };
  tbb::parallel_invoke([&] { flat[0] = flattenSurface(*surfaces[0], 0, hiddenOf(0)); },
                       [&] { flat[1] = flattenSurface(*surfaces[1], 1, hiddenOf(1)); });

  std::vector<PackChart> packed;
  for (auto& charts : flat)
    for (auto& c : charts) {
      // A chart mostly hidden is packed small: the visible surface gets its texels.
      const SurfaceMesh& m = *surfaces[std::size_t(c.surface)];
      double area = 0, hidden = 0;
      for (const std::uint32_t t : hidden_triangles ? c.triangles : std::vector<std::uint32_t>{}) {
        const auto& tri = m.triangles[t];
        const double a = triangleArea(m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]);
        area += a;
        const auto& flags = (*hidden_triangles)[std::size_t(c.surface)];
        if (t < flags.size() && flags[t]) hidden += a;
      }
      PackChart chart{c.uv.uv, c.uv.corners};
      if (area > 0 && hidden >= kHiddenShare * area)
        for (auto& uv : chart.uv) uv = {uv[0] * kHiddenDensity, uv[1] * kHiddenDensity};
      packed.push_back(std::move(chart));
    }
  UvAtlas atlas;
  atlas.charts = packed.size();
  atlas.texels_per_unit = packCharts(packed, size, padding);
  std::vector<std::vector<std::array<double, 2>>> uv;
  for (PackChart& c : packed) uv.push_back(std::move(c.uv));

  atlas.meshes = meshes;
  std::array<SurfaceMesh*, 2> out{&atlas.meshes.rock, &atlas.meshes.colluvium};
  std::size_t first = 0;
  for (int s = 0; s < 2; ++s) {
    std::vector<const FlatChart*> charts;
    std::vector<std::size_t> index;
    for (const FlatChart& c : flat[s]) charts.push_back(&c), index.push_back(first + index.size());
    first += charts.size();
    if (!surfaces[s]->triangles.empty())
      *out[s] = splitAlongSeams(*surfaces[s], charts, uv, index, atlas.source_vertex[std::size_t(s)]);
  }
  return atlas;
}

double texelDensity(const AssetMeshes& meshes, int size) {
  std::vector<std::pair<double, double>> density;  // (texels per unit, area)
  double total = 0;
  for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium}) {
    if (m->uvs.size() != m->positions.size()) continue;
    for (const auto& t : m->triangles) {
      const Vec3d a = toVec3d(m->positions[t[0]]), b = toVec3d(m->positions[t[1]]), c = toVec3d(m->positions[t[2]]);
      const double area = 0.5 * length(cross(sub(b, a), sub(c, a)));
      const auto &p = m->uvs[t[0]], &q = m->uvs[t[1]], &r = m->uvs[t[2]];
      const double uv =
          0.5 * std::abs((double(q[0]) - p[0]) * (double(r[1]) - p[1]) - (double(q[1]) - p[1]) * (double(r[0]) - p[0]));
      if (area <= 0) continue;
      density.emplace_back(size * std::sqrt(uv / area), area);
      total += area;
    }
  }
  std::sort(density.begin(), density.end());
  double sum = 0;
  for (const auto& [d, area] : density)
    if ((sum += area) >= 0.5 * total) return d;
  return 0.0;
}

double uvCoverage(const AssetMeshes& meshes) {
  double covered = 0;
  for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium}) {
    if (m->uvs.size() != m->positions.size()) continue;
    for (const auto& t : m->triangles) {
      const auto &p = m->uvs[t[0]], &q = m->uvs[t[1]], &r = m->uvs[t[2]];
      covered +=
          0.5 * std::abs((double(q[0]) - p[0]) * (double(r[1]) - p[1]) - (double(q[1]) - p[1]) * (double(r[0]) - p[0]));
    }
  }
  return covered;
}

}  // namespace rockbake
