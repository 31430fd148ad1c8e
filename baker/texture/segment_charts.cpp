#include "texture/segment_charts.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <tuple>

#include "core/vec3.h"
#include "geometry/edge_table.h"

namespace rockbake {
namespace {

constexpr Vec3d kZero{0.0, 0.0, 0.0};  // normalised()'s fallback: a zero vector stays zero

constexpr std::uint32_t kNone = 0xffffffffu;
constexpr double kSoftCreaseCos = 0.866;  // cos 30°: a bend from here …
constexpr double kCreaseCos = 0.2588;     // … to cos 75° (a crease) hides a seam as well as a concavity
constexpr double kSmoothing = 0.02;       // normal smoothing reach, share of the bounding-box diagonal
constexpr double kHiddenCost = 3.0;       // a step across a hidden edge costs up to 1 + this times more
constexpr double kTurnCost = 2.0;         // … and 1 + this · (1 − cos) more, turned from the chart's normal
constexpr int kLloydIterations = 4;
constexpr int kBorderPasses = 4;

struct Surface {
  // Each triangle's normal smoothed over the asset's roughness (the cone and turn tests read
  // the surface's shape, not its grain), area and centroid.
  std::vector<Vec3d> normal, centroid;
  std::vector<double> area;
  std::vector<std::array<std::uint32_t, 3>>
      across;  // the triangle across each edge, or EdgeTable::kNone (EdgeTable::faceAcross)
  std::vector<std::array<double, 3>> step;  // cost per edge before the turn factor
  std::vector<std::array<double, 3>> seam;  // per edge: its length times how visible a seam there is
};

// How well a seam hides along the edge from a to b, 0 (in plain sight) … 1 (hidden): in a
// concavity, under colluvium or on a crease (`bend`: the cosine between the two triangles'
// own normals).
double hidden(const SurfaceMesh& mesh, std::uint32_t a, std::uint32_t b, double bend) {
  double h = std::clamp((kSoftCreaseCos - bend) / (kSoftCreaseCos - kCreaseCos), 0.0, 1.0);
  if (mesh.curvature.size() == mesh.positions.size()) {
    const double s = 0.5 * (mesh.curvature[a] + mesh.curvature[b]);  // calibrated exposure, ½ flat
    h = std::max(h, std::clamp((0.5 - s) / 0.25, 0.0, 1.0));
  }
  if (mesh.colluvium.size() == mesh.positions.size())
    h = std::max(h, std::clamp(0.5 * (mesh.colluvium[a] + mesh.colluvium[b]), 0.0, 1.0));
  return h;
}

Surface describe(const SurfaceMesh& mesh) {
  const std::size_t nt = mesh.triangles.size();
  Surface s;
  s.normal.resize(nt), s.centroid.resize(nt), s.area.resize(nt), s.step.resize(nt), s.seam.resize(nt);
  std::vector<Vec3d> own(nt);
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, edges = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3d a = toVec3d(mesh.positions[tri[0]]), b = toVec3d(mesh.positions[tri[1]]),
                c = toVec3d(mesh.positions[tri[2]]);
    const Vec3d n = cross(sub(b, a), sub(c, a));
    s.area[t] = 0.5 * length(n);
    own[t] = normalised(n, kZero);
    s.centroid[t] = scale(add(add(a, b), c), 1.0 / 3.0);
    edges += length(sub(b, a)) + length(sub(c, b)) + length(sub(a, c));
    for (int i = 0; i < 3; ++i)
      lo[i] = std::min({lo[i], a[i], b[i], c[i]}), hi[i] = std::max({hi[i], a[i], b[i], c[i]});
  }
  const EdgeTable table(mesh.triangles);
  s.across.resize(nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::uint32_t k = 0; k < 3; ++k) s.across[t][k] = table.faceAcross(std::uint32_t(3 * t + k));
  // Smoothing passes (area-weighted means over edge neighbours) reaching about kSmoothing of
  // the surface's bounding-box diagonal: the detail's grain is gone, the shape stays.
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double mean_edge = edges / double(3 * nt);
  const int passes = mean_edge > 0 ? std::clamp(int(std::lround(kSmoothing * diagonal / mean_edge)), 0, 12) : 0;
  s.normal = own;
  std::vector<Vec3d> next(nt);
  for (int pass = 0; pass < passes; ++pass) {
    for (std::size_t t = 0; t < nt; ++t) {
      Vec3d sum = scale(s.normal[t], s.area[t]);
      for (std::uint32_t u : s.across[t])
        if (u != EdgeTable::kNone) sum = add(sum, scale(s.normal[u], s.area[u]));
      next[t] = length(sum) > 0 ? normalised(sum, kZero) : s.normal[t];
    }
    std::swap(s.normal, next);
  }
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = s.across[t][k];
      if (u == EdgeTable::kNone) continue;
      const std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      const double h = hidden(mesh, a, b, dot(own[t], own[u]));
      s.step[t][k] = length(sub(s.centroid[u], s.centroid[t])) * (1.0 + kHiddenCost * h);
      s.seam[t][k] = length(sub(toVec3d(mesh.positions[b]), toVec3d(mesh.positions[a]))) * (1.0 - h);
    }
  return s;
}

// One multi-source Dijkstra over the triangles not yet in a chart, from the seeds (with
// `cone`) or from the charts' borders (without).
void grow(const Surface& s, const std::vector<std::uint32_t>& seeds, const std::vector<Vec3d>& axes,
          std::vector<std::uint32_t>& chart, bool cone);

struct Entry {
  double cost;
  std::uint32_t triangle, chart;
  bool operator>(const Entry& o) const {
    return std::tie(cost, triangle, chart) > std::tie(o.cost, o.triangle, o.chart);
  }
};
using Queue = std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>>;

double turn(const Surface& s, std::uint32_t t, const Vec3d& axis) {
  return 1.0 + kTurnCost * (1.0 - dot(s.normal[t], axis));
}

// Grows every chart at once from its seed (multi-source Dijkstra); a triangle joins only a
// chart whose axis is within the cone. Then triangles no chart could take go to the chart
// that reaches them first without the cone (segmentCharts' merge and the flattening's
// checks judge the result); only a piece no seed reaches at all keeps kNone.
void partition(const Surface& s, const std::vector<std::uint32_t>& seeds, const std::vector<Vec3d>& axes,
               std::vector<std::uint32_t>& chart) {
  grow(s, seeds, axes, chart, true);
  grow(s, seeds, axes, chart, false);
}

void grow(const Surface& s, const std::vector<std::uint32_t>& seeds, const std::vector<Vec3d>& axes,
          std::vector<std::uint32_t>& chart, bool cone) {
  const std::size_t nt = s.area.size();
  std::vector<double> best(nt, std::numeric_limits<double>::infinity());
  Queue queue;
  if (cone) {
    chart.assign(nt, kNone);
    for (std::uint32_t k = 0; k < seeds.size(); ++k)
      if (dot(s.normal[seeds[k]], axes[k]) >= kMaxChartCos) queue.push({0.0, seeds[k], k});
  } else {
    for (std::uint32_t t = 0; t < nt; ++t) {
      if (chart[t] == kNone) continue;
      for (int j = 0; j < 3; ++j) {
        const std::uint32_t u = s.across[t][j];
        if (u == EdgeTable::kNone || chart[u] != kNone) continue;
        const double cost = s.step[t][j] * turn(s, u, axes[chart[t]]);
        if (cost < best[u]) best[u] = cost, queue.push({cost, u, chart[t]});
      }
    }
  }
  while (!queue.empty()) {
    const Entry e = queue.top();
    queue.pop();
    if (chart[e.triangle] != kNone) continue;
    chart[e.triangle] = e.chart;
    for (int j = 0; j < 3; ++j) {
      const std::uint32_t u = s.across[e.triangle][j];
      if (u == EdgeTable::kNone || chart[u] != kNone || (cone && dot(s.normal[u], axes[e.chart]) < kMaxChartCos))
        continue;
      const double cost = e.cost + s.step[e.triangle][j] * turn(s, u, axes[e.chart]);
      if (cost < best[u]) {
        best[u] = cost;
        queue.push({cost, u, e.chart});
      }
    }
  }
}

// Gives every unassigned triangle a chart: grows one chart at a time from the lowest
// unassigned triangle, its axis the running mean of its normals.
void fillUnassigned(const Surface& s, std::vector<std::uint32_t>& chart, std::vector<std::uint32_t>& seeds,
                    std::vector<Vec3d>& axes) {
  const std::size_t nt = s.area.size();
  std::vector<double> best(nt, std::numeric_limits<double>::infinity());
  std::vector<std::uint32_t> touched;  // where `best` was set, reset before the next chart
  for (std::uint32_t seed = 0; seed < nt; ++seed) {
    if (chart[seed] != kNone) continue;
    for (std::uint32_t t : touched) best[t] = std::numeric_limits<double>::infinity();
    touched.clear();
    const auto k = std::uint32_t(seeds.size());
    Vec3d sum{0, 0, 0};
    Vec3d axis = s.normal[seed];
    Queue queue;
    queue.push({0.0, seed, k});
    best[seed] = 0;
    touched.push_back(seed);
    while (!queue.empty()) {
      const Entry e = queue.top();
      queue.pop();
      if (chart[e.triangle] != kNone || (e.triangle != seed && dot(s.normal[e.triangle], axis) < kMaxChartCos))
        continue;
      chart[e.triangle] = k;
      sum = add(sum, scale(s.normal[e.triangle], std::max(s.area[e.triangle], 1e-30)));
      if (length(sum) > 0) axis = normalised(sum, kZero);
      for (int j = 0; j < 3; ++j) {
        const std::uint32_t u = s.across[e.triangle][j];
        if (u == EdgeTable::kNone || chart[u] != kNone || dot(s.normal[u], axis) < kMaxChartCos) continue;
        const double cost = e.cost + s.step[e.triangle][j] * turn(s, u, axis);
        if (cost < best[u]) {
          best[u] = cost;
          touched.push_back(u);
          queue.push({cost, u, k});
        }
      }
    }
    seeds.push_back(seed);
    axes.push_back(axis);
  }
}

// Each chart's axis becomes its mean normal and its seed its innermost triangle (most
// steps from the chart's border; ties: the one nearest the axis, then the lowest).
void fit(const Surface& s, const std::vector<std::uint32_t>& chart, std::vector<std::uint32_t>& seeds,
         std::vector<Vec3d>& axes) {
  const std::size_t nt = s.area.size(), nc = seeds.size();
  std::vector<Vec3d> sum(nc, Vec3d{0, 0, 0});
  for (std::size_t t = 0; t < nt; ++t)
    sum[chart[t]] = add(sum[chart[t]], scale(s.normal[t], std::max(s.area[t], 1e-30)));
  for (std::size_t k = 0; k < nc; ++k)
    if (length(sum[k]) > 0) axes[k] = normalised(sum[k], kZero);
  // Breadth-first depth from each chart's border, inside the chart.
  std::vector<std::uint32_t> depth(nt, kNone), frontier;
  for (std::uint32_t t = 0; t < nt; ++t)
    for (int j = 0; j < 3; ++j) {
      const std::uint32_t u = s.across[t][j];
      if (u == EdgeTable::kNone || chart[u] != chart[t]) {
        depth[t] = 0;
        frontier.push_back(t);
        break;
      }
    }
  for (std::size_t i = 0; i < frontier.size(); ++i) {
    const std::uint32_t t = frontier[i];
    for (int j = 0; j < 3; ++j) {
      const std::uint32_t u = s.across[t][j];
      if (u != EdgeTable::kNone && depth[u] == kNone && chart[u] == chart[t]) {
        depth[u] = depth[t] + 1;
        frontier.push_back(u);
      }
    }
  }
  std::vector<std::uint32_t> inner(nc, kNone);
  for (std::uint32_t t = 0; t < nt; ++t) {
    std::uint32_t& best = inner[chart[t]];
    const Vec3d& axis = axes[chart[t]];
    if (best == kNone || depth[t] > depth[best] ||
        (depth[t] == depth[best] && dot(s.normal[t], axis) > dot(s.normal[best], axis)))
      best = t;
  }
  for (std::size_t k = 0; k < nc; ++k) seeds[k] = inner[k];
}

// Drops charts that no triangle took and numbers the rest by their lowest triangle.
std::uint32_t renumber(std::vector<std::uint32_t>& chart, std::vector<std::uint32_t>& seeds, std::vector<Vec3d>& axes) {
  std::vector<std::uint32_t> order(seeds.size(), kNone);
  std::vector<std::uint32_t> kept_seeds;
  std::vector<Vec3d> kept_axes;
  for (std::uint32_t& c : chart) {
    if (order[c] == kNone) {
      order[c] = std::uint32_t(kept_seeds.size());
      kept_seeds.push_back(seeds[c]);
      kept_axes.push_back(axes[c]);
    }
    c = order[c];
  }
  seeds = std::move(kept_seeds);
  axes = std::move(kept_axes);
  return std::uint32_t(seeds.size());
}

// Merges neighbouring charts while their union keeps every normal within the cone of its
// mean: smallest chart first, into the neighbour it shares the longest visible seam with.
void mergeWithinNormalCone(const Surface& s, std::vector<std::uint32_t>& chart, std::uint32_t count) {
  std::vector<std::vector<std::uint32_t>> members(count);
  std::vector<Vec3d> sum(count, Vec3d{0, 0, 0});
  std::vector<double> area(count, 0.0);
  for (std::uint32_t t = 0; t < chart.size(); ++t) {
    members[chart[t]].push_back(t);
    sum[chart[t]] = add(sum[chart[t]], scale(s.normal[t], std::max(s.area[t], 1e-30)));
    area[chart[t]] += s.area[t];
  }
  const auto fits = [&](std::uint32_t a, std::uint32_t b) {
    const Vec3d axis = normalised(add(sum[a], sum[b]), kZero);
    for (std::uint32_t k : {a, b})
      for (std::uint32_t t : members[k])
        if (dot(s.normal[t], axis) < kMaxChartCos) return false;
    return true;
  };
  for (bool merged = true; merged;) {
    merged = false;
    std::vector<std::uint32_t> order;
    for (std::uint32_t k = 0; k < count; ++k)
      if (!members[k].empty()) order.push_back(k);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return area[a] < area[b]; });
    for (std::uint32_t a : order) {
      if (members[a].empty()) continue;
      std::vector<std::pair<double, std::uint32_t>> shared;  // (visible seam length, neighbour)
      for (std::uint32_t t : members[a])
        for (int j = 0; j < 3; ++j) {
          const std::uint32_t u = s.across[t][j];
          if (u == EdgeTable::kNone || chart[u] == a) continue;
          const auto it =
              std::find_if(shared.begin(), shared.end(), [&](const auto& p) { return p.second == chart[u]; });
          if (it == shared.end())
            shared.push_back({s.seam[t][j], chart[u]});
          else
            it->first += s.seam[t][j];
        }
      std::stable_sort(shared.begin(), shared.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
      for (const auto& [length, b] : shared) {
        if (!fits(a, b)) continue;
        const std::uint32_t into = members[b].size() >= members[a].size() ? b : a, from = into == b ? a : b;
        for (std::uint32_t t : members[from]) chart[t] = into;
        members[into].insert(members[into].end(), members[from].begin(), members[from].end());
        members[from].clear();
        sum[into] = add(sum[into], sum[from]);
        area[into] += area[from];
        merged = true;
        break;
      }
    }
  }
}

// Evens the charts' borders: a triangle with two or three edge neighbours in one other chart,
// whose normal is within that chart's cone, moves there (it is a leaf of its own chart, so
// that stays connected). A few passes, each deciding from the pass before.
void smoothBorders(const Surface& s, std::vector<std::uint32_t>& chart, std::uint32_t count) {
  std::vector<Vec3d> sum(count, Vec3d{0, 0, 0});
  for (std::uint32_t t = 0; t < chart.size(); ++t)
    sum[chart[t]] = add(sum[chart[t]], scale(s.normal[t], std::max(s.area[t], 1e-30)));
  for (int pass = 0; pass < kBorderPasses; ++pass) {
    std::vector<std::uint32_t> next = chart;
    bool moved = false;
    for (std::uint32_t t = 0; t < chart.size(); ++t) {
      const auto& n = s.across[t];
      for (int j = 0; j < 3; ++j) {
        const std::uint32_t u = n[j], v = n[(j + 1) % 3];
        if (u == EdgeTable::kNone || v == EdgeTable::kNone || chart[u] == chart[t] || chart[u] != chart[v]) continue;
        if (dot(s.normal[t], normalised(sum[chart[u]], kZero)) < kMaxChartCos) continue;
        next[t] = chart[u];
        moved = true;
        break;
      }
    }
    if (!moved) break;
    for (std::uint32_t t = 0; t < chart.size(); ++t)
      if (next[t] != chart[t]) {
        const Vec3d w = scale(s.normal[t], std::max(s.area[t], 1e-30));
        sum[chart[t]] = sub(sum[chart[t]], w);
        sum[next[t]] = add(sum[next[t]], w);
      }
    chart = std::move(next);
  }
}

// Makes every chart edge-connected: a chart in pieces becomes one chart per piece.
std::uint32_t splitPieces(const Surface& s, std::vector<std::uint32_t>& chart) {
  std::vector<std::uint32_t> piece(chart.size(), kNone), queue;
  std::uint32_t count = 0;
  for (std::uint32_t t = 0; t < chart.size(); ++t) {
    if (piece[t] != kNone) continue;
    piece[t] = count;
    queue.assign(1, t);
    for (std::size_t q = 0; q < queue.size(); ++q)
      for (std::uint32_t u : s.across[queue[q]])
        if (u != EdgeTable::kNone && piece[u] == kNone && chart[u] == chart[t]) piece[u] = count, queue.push_back(u);
    ++count;
  }
  chart = std::move(piece);
  return count;
}

}  // namespace

std::vector<std::uint32_t> segmentCharts(const SurfaceMesh& mesh) {
  const std::size_t nt = mesh.triangles.size();
  std::vector<std::uint32_t> chart(nt, kNone);
  if (nt == 0) return chart;
  const Surface s = describe(mesh);
  std::vector<std::uint32_t> seeds;
  std::vector<Vec3d> axes;
  fillUnassigned(s, chart, seeds, axes);
  for (int iteration = 0; iteration < kLloydIterations; ++iteration) {
    renumber(chart, seeds, axes);
    fit(s, chart, seeds, axes);
    partition(s, seeds, axes, chart);
    fillUnassigned(s, chart, seeds, axes);
  }
  mergeWithinNormalCone(s, chart, renumber(chart, seeds, axes));
  smoothBorders(s, chart, renumber(chart, seeds, axes));
  splitPieces(s, chart);
  return chart;
}

}  // namespace rockbake
