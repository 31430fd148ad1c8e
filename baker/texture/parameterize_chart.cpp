#include "texture/parameterize_chart.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>
#include <utility>

#include "core/vec3.h"

namespace rockbake {
namespace {

constexpr Vec3d kZero{0.0, 0.0, 0.0};  // normalised()'s fallback: a zero vector stays zero
using UV = std::array<double, 2>;

constexpr double kMaxScale = 2.0;         // linear texel-density ratio to the chart's mean …
constexpr double kMaxUnevenShare = 0.10;  // … that at most this share of its area may exceed

struct LocalChart {
  std::vector<std::uint32_t> vertices;                            // mesh indices
  std::vector<std::array<std::uint32_t, 3>> tris;                 // local indices
  std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary;  // local half-edges used once
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;     // every edge once
};

// The chart's own vertices: a mesh vertex the chart touches in two fans (its triangles meet
// there at a point only) becomes two chart vertices, so a pinch is a boundary like any other.
LocalChart localise(const SurfaceMesh& mesh, const std::vector<std::uint32_t>& triangles) {
  const std::size_t nt = triangles.size();
  // Corners 3i + k; corners of one mesh vertex joined across each edge two chart triangles share.
  std::vector<std::uint32_t> parent(3 * nt);
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const auto find = [&](std::uint32_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  const auto join = [&](std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  const auto key = [](std::uint32_t a, std::uint32_t b) { return std::uint64_t(a) << 32 | b; };
  std::unordered_map<std::uint64_t, std::uint32_t> half;  // (mesh a, mesh b) → corner of a
  half.reserve(3 * nt);
  for (std::uint32_t i = 0; i < nt; ++i)
    for (std::uint32_t k = 0; k < 3; ++k) {
      const auto& t = mesh.triangles[triangles[i]];
      half.emplace(key(t[k], t[(k + 1) % 3]), 3 * i + k);
    }
  for (std::uint32_t i = 0; i < nt; ++i)
    for (std::uint32_t k = 0; k < 3; ++k) {
      const auto& t = mesh.triangles[triangles[i]];
      const auto back = half.find(key(t[(k + 1) % 3], t[k]));
      if (back == half.end()) continue;
      const std::uint32_t j = back->second / 3, m = back->second % 3;  // corner m of j holds t[k + 1]
      join(3 * i + k, 3 * j + (m + 1) % 3);
      join(3 * i + (k + 1) % 3, 3 * j + m);
    }
  LocalChart c;
  std::unordered_map<std::uint32_t, std::uint32_t> local;  // corner root → chart vertex
  local.reserve(2 * nt);
  for (std::uint32_t i = 0; i < nt; ++i) {
    std::array<std::uint32_t, 3> l{};
    for (std::uint32_t k = 0; k < 3; ++k) {
      const auto [it, fresh] = local.try_emplace(find(3 * i + k), std::uint32_t(c.vertices.size()));
      if (fresh) c.vertices.push_back(mesh.triangles[triangles[i]][k]);
      l[k] = it->second;
    }
    c.tris.push_back(l);
  }
  // Half-edges: an edge used in both directions is interior, once is boundary.
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(3 * nt);
  for (const auto& t : c.tris)
    for (int k = 0; k < 3; ++k) ++uses[key(t[k], t[(k + 1) % 3])];
  for (const auto& t : c.tris)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (uses.find(key(b, a)) == uses.end()) {
        c.boundary.emplace_back(a, b);
        c.edges.emplace_back(a, b);
      } else if (a < b) {
        c.edges.emplace_back(a, b);
      }
    }
  return c;
}

// One boundary loop and Euler characteristic 1.
bool isDisk(const LocalChart& c) {
  const long euler = long(c.vertices.size()) - long(c.edges.size()) + long(c.tris.size());
  if (euler != 1 || c.boundary.empty()) return false;
  std::unordered_map<std::uint32_t, std::uint32_t> next;
  for (const auto& [a, b] : c.boundary)
    if (!next.emplace(a, b).second) return false;  // two boundary edges leave one vertex: a pinch
  std::size_t steps = 0;
  std::uint32_t v = c.boundary[0].first;
  do {
    const auto it = next.find(v);
    if (it == next.end()) return false;
    v = it->second;
    ++steps;
  } while (v != c.boundary[0].first && steps <= c.boundary.size());
  return steps == c.boundary.size();
}

// The LSCM energy's normal equations with two vertices pinned; returns uv per local vertex.
// The energy is a complex least-squares problem in z = u + i v (one complex row per triangle,
// Lévy et al. 2002, §3), so its normal equations are Hermitian in the m free vertices: solved
// as such they have a quarter of the entries, and half the unknowns to order, of the same
// equations split into real u and v.
std::vector<UV> solveLscm(const SurfaceMesh& mesh, const LocalChart& c) {
  using Complex = std::complex<double>;
  const std::size_t n = c.vertices.size();
  const auto position = [&](std::uint32_t l) { return toVec3d(mesh.positions[c.vertices[l]]); };
  // Pins: the boundary vertex farthest from the first boundary vertex, and the one farthest from it.
  const auto farthest = [&](std::uint32_t from) {
    std::uint32_t best = from;
    double best_d = -1;
    for (const auto& e : c.boundary) {
      const double d = length(sub(position(e.first), position(from)));
      if (d > best_d) best_d = d, best = e.first;
    }
    return best;
  };
  const std::uint32_t p0 = farthest(c.boundary[0].first), p1 = farthest(p0);
  std::vector<UV> uv(n, UV{0, 0});
  uv[p1] = {std::max(length(sub(position(p1), position(p0))), 1e-12), 0.0};
  std::vector<int> unknown(n, -1);
  int m = 0;
  for (std::uint32_t v = 0; v < n; ++v)
    if (v != p0 && v != p1) unknown[v] = m++;
  if (m == 0) return uv;

  std::vector<Eigen::Triplet<Complex>> entries;
  entries.reserve(9 * c.tris.size() + 4 * c.edges.size());
  Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(m);
  // One complex row: up to three (vertex, coefficient) terms. Its normal equations take
  // conj(c_i) c_j at (i, j) and move the pinned vertices' terms to the right-hand side.
  struct Row {
    std::array<std::pair<std::uint32_t, Complex>, 3> terms;
    int size = 0;
    void add(std::uint32_t v, Complex coef) { terms[std::size_t(size++)] = {v, coef}; }
    const std::pair<std::uint32_t, Complex>* begin() const { return terms.data(); }
    const std::pair<std::uint32_t, Complex>* end() const { return terms.data() + size; }
  };
  const auto addRow = [&](const Row& row) {
    Complex pinned = 0;
    for (const auto& [v, coef] : row)
      if (unknown[v] < 0) pinned += coef * Complex(uv[v][0], uv[v][1]);
    for (const auto& [vi, ci] : row) {
      const int i = unknown[vi];
      if (i < 0) continue;
      rhs[i] -= std::conj(ci) * pinned;
      for (const auto& [vj, cj] : row)
        if (const int j = unknown[vj]; j >= 0) entries.emplace_back(i, j, std::conj(ci) * cj);
    }
  };
  for (const auto& t : c.tris) {
    const Vec3d a = position(t[0]), b = position(t[1]), cc = position(t[2]);
    const Vec3d e1 = sub(b, a), e2 = sub(cc, a), normal = cross(e1, e2);
    const double area = 0.5 * length(normal);
    if (area <= 1e-14 * dot(e1, e1) || area <= 0) continue;  // a zero-area triangle says nothing about angles
    const Vec3d x = normalised(e1, kZero), y = normalised(cross(normal, e1), kZero);
    const std::array<double, 3> px{0.0, length(e1), dot(e2, x)}, py{0.0, 0.0, dot(e2, y)};
    const double w = 1.0 / std::sqrt(area);
    Row row;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      row.add(t[j], Complex((py[j1] - py[j2]) * w, (px[j2] - px[j1]) * w));  // W_j
    }
    addRow(row);
  }
  // A faint membrane over the edges keeps the system definite where triangles carry no
  // area (a vertex only zero-area triangles touch); far below the conformal terms elsewhere.
  const double faint = std::sqrt(1e-7);
  for (const auto& [a, b] : c.edges) {
    Row row;
    row.add(a, faint);
    row.add(b, -faint);
    addRow(row);
  }
  Eigen::SparseMatrix<Complex> normal(m, m);
  normal.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<Complex>> solver(normal);
  if (solver.info() != Eigen::Success) return {};
  const Eigen::VectorXcd z = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !z.allFinite()) return {};
  for (std::uint32_t v = 0; v < n; ++v)
    if (unknown[v] >= 0) uv[v] = {z[unknown[v]].real(), z[unknown[v]].imag()};
  return uv;
}

double signedArea(const UV& a, const UV& b, const UV& c) {
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

// Whether two boundary segments that share no vertex cross (a uniform grid finds candidates).
bool boundaryCrosses(const LocalChart& c, const std::vector<UV>& uv) {
  const std::size_t nb = c.boundary.size();
  if (nb < 4) return false;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300}, total = 0;
  for (const auto& [a, b] : c.boundary) {
    for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], uv[a][i]), hi[i] = std::max(hi[i], uv[a][i]);
    total += std::hypot(uv[b][0] - uv[a][0], uv[b][1] - uv[a][1]);
  }
  const double cell = std::max(total / double(nb), 1e-12);
  const auto cells = [&](int i) { return std::max(1, std::min(4096, int((hi[i] - lo[i]) / cell) + 1)); };
  const int gx = cells(0), gy = cells(1);
  const auto cellOf = [&](double v, int i, int g) { return std::clamp(int((v - lo[i]) / cell), 0, g - 1); };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (std::uint32_t e = 0; e < nb; ++e) {
    const UV &p = uv[c.boundary[e].first], &q = uv[c.boundary[e].second];
    const int x0 = cellOf(std::min(p[0], q[0]), 0, gx), x1 = cellOf(std::max(p[0], q[0]), 0, gx);
    const int y0 = cellOf(std::min(p[1], q[1]), 1, gy), y1 = cellOf(std::max(p[1], q[1]), 1, gy);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) grid[std::uint64_t(y) * std::uint64_t(gx) + std::uint64_t(x)].push_back(e);
  }
  const auto orient = [](const UV& a, const UV& b, const UV& p) {
    const double d = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    return (d > 0) - (d < 0);
  };
  for (const auto& [key, list] : grid)
    for (std::size_t i = 0; i < list.size(); ++i)
      for (std::size_t j = i + 1; j < list.size(); ++j) {
        const auto& e = c.boundary[list[i]];
        const auto& f = c.boundary[list[j]];
        if (e.first == f.first || e.first == f.second || e.second == f.first || e.second == f.second) continue;
        const UV &a = uv[e.first], &b = uv[e.second], &p = uv[f.first], &q = uv[f.second];
        if (orient(a, b, p) * orient(a, b, q) < 0 && orient(p, q, a) * orient(p, q, b) < 0) return true;
      }
  return false;
}

}  // namespace

ChartUv parameterizeChart(const SurfaceMesh& mesh, const std::vector<std::uint32_t>& triangles) {
  const LocalChart c = localise(mesh, triangles);
  ChartUv out;
  out.vertices = c.vertices;
  out.corners = c.tris;
  if (!isDisk(c)) {
    out.status = ChartStatus::NotDisk;
    return out;
  }
  if (c.tris.size() == 1) {
    // In its own plane (a zero-area triangle laid along its first edge).
    const Vec3d a = toVec3d(mesh.positions[c.vertices[0]]), b = toVec3d(mesh.positions[c.vertices[1]]),
                cc = toVec3d(mesh.positions[c.vertices[2]]);
    const Vec3d e1 = sub(b, a), e2 = sub(cc, a);
    const Vec3d x = normalised(e1, kZero), y = normalised(cross(cross(e1, e2), e1), kZero);
    out.uv = {UV{0, 0}, UV{length(e1), 0}, UV{dot(e2, x), dot(e2, y)}};
    return out;
  }
  out.uv = solveLscm(mesh, c);
  if (out.uv.size() != c.vertices.size()) {
    out.status = ChartStatus::Folded;  // the solver failed: treat as unusable, split
    return out;
  }
  // Orientation as the surface's, area as the surface's.
  std::vector<double> area3(c.tris.size()), area2(c.tris.size());
  double sum3 = 0, sum2 = 0;
  for (std::size_t i = 0; i < c.tris.size(); ++i) {
    const auto& t = c.tris[i];
    const Vec3d a = toVec3d(mesh.positions[c.vertices[t[0]]]), b = toVec3d(mesh.positions[c.vertices[t[1]]]),
                cc = toVec3d(mesh.positions[c.vertices[t[2]]]);
    area3[i] = 0.5 * length(cross(sub(b, a), sub(cc, a)));
    area2[i] = signedArea(out.uv[t[0]], out.uv[t[1]], out.uv[t[2]]);
    sum3 += area3[i];
    sum2 += area2[i];
  }
  if (sum2 < 0) {
    for (UV& p : out.uv) p[0] = -p[0];
    for (double& a : area2) a = -a;
    sum2 = -sum2;
  }
  if (sum2 > 0 && sum3 > 0) {
    const double s = std::sqrt(sum3 / sum2);
    for (UV& p : out.uv) p = {p[0] * s, p[1] * s};
    for (double& a : area2) a *= s * s;
  }
  const double tiny = 1e-9 * sum3 / double(c.tris.size());
  double uneven = 0;
  for (std::size_t i = 0; i < c.tris.size(); ++i) {
    if (area2[i] < -tiny) {
      out.status = ChartStatus::Folded;
      return out;
    }
    if (area3[i] > 0) {
      const double r = area2[i] / area3[i];  // squared linear scale against the chart's mean
      if (r > kMaxScale * kMaxScale || r < 1.0 / (kMaxScale * kMaxScale)) uneven += area3[i];
    }
  }
  if (boundaryCrosses(c, out.uv)) {
    out.status = ChartStatus::SelfOverlapping;
    return out;
  }
  if (uneven > kMaxUnevenShare * sum3) out.status = ChartStatus::Stretched;
  return out;
}

std::array<std::vector<std::uint32_t>, 2> splitChart(const SurfaceMesh& mesh, const EdgeTable& edges,
                                                     const std::vector<std::uint32_t>& triangles) {
  std::unordered_map<std::uint32_t, std::uint32_t> index;  // mesh triangle → position in `triangles`
  index.reserve(2 * triangles.size());
  for (std::uint32_t i = 0; i < triangles.size(); ++i) index.emplace(triangles[i], i);
  const std::size_t n = triangles.size();
  const auto neighbours = [&](std::uint32_t i, auto&& visit) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t u = edges.faceAcross(3 * triangles[i] + k);
      if (u == EdgeTable::kNone) continue;
      const auto it = index.find(u);
      if (it != index.end()) visit(it->second);
    }
  };
  const auto farthest = [&](std::uint32_t from) {
    std::vector<std::uint32_t> hops(n, EdgeTable::kNone), queue{from};
    hops[from] = 0;
    for (std::size_t q = 0; q < queue.size(); ++q)
      neighbours(queue[q], [&](std::uint32_t j) {
        if (hops[j] == EdgeTable::kNone) hops[j] = hops[queue[q]] + 1, queue.push_back(j);
      });
    return queue.back();
  };
  const std::uint32_t a = farthest(0), b = farthest(a);
  std::vector<Vec3d> centre(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& t = mesh.triangles[triangles[i]];
    centre[i] =
        scale(add(add(toVec3d(mesh.positions[t[0]]), toVec3d(mesh.positions[t[1]])), toVec3d(mesh.positions[t[2]])),
              1.0 / 3.0);
  }
  // Nearest seed by path length over centroids (Dijkstra from both seeds at once).
  std::vector<int> side(n, -1);
  std::vector<double> best(n, std::numeric_limits<double>::infinity());
  using Entry = std::tuple<double, std::uint32_t, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  queue.emplace(0.0, a, 0);
  if (b != a) queue.emplace(0.0, b, 1);
  while (!queue.empty()) {
    const auto [d, i, s] = queue.top();
    queue.pop();
    if (side[i] >= 0) continue;
    side[i] = s;
    neighbours(i, [&](std::uint32_t j) {
      const double dj = d + length(sub(centre[j], centre[i]));
      if (side[j] < 0 && dj < best[j]) best[j] = dj, queue.emplace(dj, j, s);
    });
  }
  std::array<std::vector<std::uint32_t>, 2> halves;
  for (std::size_t i = 0; i < n; ++i) halves[side[i] < 0 ? 1 : side[i]].push_back(triangles[i]);
  if (halves[1].empty() && n > 1) {  // b == a: one triangle's worth of chart moves over
    halves[1].push_back(halves[0].back());
    halves[0].pop_back();
  }
  return halves;
}

}  // namespace rockbake
