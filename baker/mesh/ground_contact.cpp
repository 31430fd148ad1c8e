#include "mesh/ground_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

namespace rockbake {
namespace {

// "No contact in this row": large but finite, so that the envelope's arithmetic stays exact enough.
constexpr double kFar = 1e20;

// The 1-D squared distance transform of sampled function f (Felzenszwalb and Huttenlocher,
// "Distance transforms of sampled functions", Theory of Computing 8, 2012): d(q) is the lower
// envelope of the parabolas (q - p)² + f(p), in cell units. v, z: scratch of n and n + 1.
void distance1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v, std::vector<double>& z) {
  const int n = int(f.size());
  int k = 0;
  v[0] = 0;
  z[0] = -kFar;
  z[1] = kFar;
  const auto at = [&](int q) { return f[std::size_t(q)] + double(q) * q; };
  for (int q = 1; q < n; ++q) {
    double s = (at(q) - at(v[std::size_t(k)])) / (2.0 * (q - v[std::size_t(k)]));
    while (s <= z[std::size_t(k)]) {
      --k;
      s = (at(q) - at(v[std::size_t(k)])) / (2.0 * (q - v[std::size_t(k)]));
    }
    ++k;
    v[std::size_t(k)] = q;
    z[std::size_t(k)] = s;
    z[std::size_t(k) + 1] = kFar;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[std::size_t(k) + 1] < q) ++k;
    const int p = v[std::size_t(k)];
    d[std::size_t(q)] = double(q - p) * (q - p) + f[std::size_t(p)];
  }
}

}  // namespace

std::vector<std::array<double, 2>> groundCapRim(const SurfaceMesh& mesh, double ground, double eps, double spacing) {
  std::vector<std::uint8_t> on_rim(mesh.positions.size(), 0);
  std::vector<std::array<double, 2>> rim;
  const auto low = [&](std::uint32_t v) { return double(mesh.positions[v][2]) <= ground + eps; };
  for (const auto& t : mesh.triangles) {
    if (low(t[0]) && low(t[1]) && low(t[2])) continue;  // on the cap
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = t[std::size_t(k)], w = t[std::size_t((k + 1) % 3)];
      if (low(v)) on_rim[v] = 1;
      if (!low(v) || !low(w)) continue;  // a rim edge: its other triangle is the cap's
      const auto& a = mesh.positions[v];
      const auto& b = mesh.positions[w];
      const double l = std::hypot(double(b[0]) - a[0], double(b[1]) - a[1]);
      const int steps = spacing > 0 ? int(std::ceil(l / spacing)) : 1;
      for (int i = 1; i < steps; ++i) {
        const double f = double(i) / steps;
        rim.push_back({a[0] + f * (double(b[0]) - a[0]), a[1] + f * (double(b[1]) - a[1])});
      }
    }
  }
  for (std::size_t v = 0; v < on_rim.size(); ++v)
    if (on_rim[v]) rim.push_back({double(mesh.positions[v][0]), double(mesh.positions[v][1])});
  return rim;
}

std::vector<std::array<double, 2>> groundContactPoints(const AssetMeshes& meshes, double ground, double eps,
                                                       double shared, double spacing) {
  const std::vector<std::array<double, 2>> rock = groundCapRim(meshes.rock, ground, eps, spacing);
  const std::vector<std::array<double, 2>> colluvium = groundCapRim(meshes.colluvium, ground, eps, spacing);
  // A rim point with one of the other surface's within `shared` is buried: found through buckets
  // of `shared` across.
  const double s2 = shared * shared;
  const auto key = [&](const std::array<double, 2>& a) {
    return std::pair{std::int64_t(std::floor(a[0] / shared)), std::int64_t(std::floor(a[1] / shared))};
  };
  const auto buckets = [&](const std::vector<std::array<double, 2>>& points) {
    std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::array<double, 2>>> b;
    for (const auto& p : points) b[key(p)].push_back(p);
    return b;
  };
  const auto rock_buckets = buckets(rock), colluvium_buckets = buckets(colluvium);
  const auto buried = [&](const std::array<double, 2>& a, const auto& other) {
    const auto [i, j] = key(a);
    for (std::int64_t dj = -1; dj <= 1; ++dj)
      for (std::int64_t di = -1; di <= 1; ++di) {
        const auto found = other.find({i + di, j + dj});
        if (found == other.end()) continue;
        for (const auto& b : found->second)
          if ((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) < s2) return true;
      }
    return false;
  };
  std::vector<std::array<double, 2>> contact;
  for (const auto& a : rock)
    if (!buried(a, colluvium_buckets)) contact.push_back(a);
  for (const auto& a : colluvium)
    if (!buried(a, rock_buckets)) contact.push_back(a);
  return contact;
}

PlaneDistance::PlaneDistance(const std::vector<std::array<double, 2>>& points, std::array<double, 2> lo,
                             std::array<double, 2> hi, double cell)
    : cell_(cell) {
  if (points.empty() || !(hi[0] >= lo[0]) || !(hi[1] >= lo[1])) return;
  x0_ = lo[0] - cell_, y0_ = lo[1] - cell_;
  nx_ = int(std::ceil((hi[0] - lo[0]) / cell_)) + 3;
  ny_ = int(std::ceil((hi[1] - lo[1]) / cell_)) + 3;
  std::vector<double> f(std::size_t(nx_) * std::size_t(ny_), kFar);
  for (const auto& p : points) {
    const int i = std::clamp(int((p[0] - x0_) / cell_), 0, nx_ - 1);
    const int j = std::clamp(int((p[1] - y0_) / cell_), 0, ny_ - 1);
    f[std::size_t(i) + std::size_t(nx_) * std::size_t(j)] = 0.0;
  }
  // Rows, then columns; squared distances in cells.
  const int n = std::max(nx_, ny_);
  std::vector<double> line, out, z(static_cast<std::size_t>(n) + 1);
  std::vector<int> v(static_cast<std::size_t>(n));
  for (int j = 0; j < ny_; ++j) {
    line.assign(f.begin() + std::ptrdiff_t(j) * nx_, f.begin() + std::ptrdiff_t(j + 1) * nx_);
    out.resize(std::size_t(nx_));
    distance1d(line, out, v, z);
    std::copy(out.begin(), out.end(), f.begin() + std::ptrdiff_t(j) * nx_);
  }
  for (int i = 0; i < nx_; ++i) {
    line.resize(std::size_t(ny_)), out.resize(std::size_t(ny_));
    for (int j = 0; j < ny_; ++j) line[std::size_t(j)] = f[std::size_t(i) + std::size_t(nx_) * std::size_t(j)];
    distance1d(line, out, v, z);
    for (int j = 0; j < ny_; ++j) f[std::size_t(i) + std::size_t(nx_) * std::size_t(j)] = out[std::size_t(j)];
  }
  distance_.resize(f.size());
  for (std::size_t c = 0; c < f.size(); ++c) distance_[c] = std::sqrt(f[c]) * cell_;
}

double PlaneDistance::at(double x, double y) const {
  if (distance_.empty()) return std::numeric_limits<double>::infinity();
  // Cell centres sit at x0 + (i + ½) cell; a point marks the cell it falls in.
  const double u = (x - x0_) / cell_ - 0.5, w = (y - y0_) / cell_ - 0.5;
  const double cu = std::clamp(u, 0.0, double(nx_ - 1)), cw = std::clamp(w, 0.0, double(ny_ - 1));
  const int i = std::min(int(cu), nx_ - 2), j = std::min(int(cw), ny_ - 2);
  const double fu = cu - i, fw = cw - j;
  const auto d = [&](int a, int b) { return distance_[std::size_t(a) + std::size_t(nx_) * std::size_t(b)]; };
  const double inside =
      (1 - fw) * ((1 - fu) * d(i, j) + fu * d(i + 1, j)) + fw * ((1 - fu) * d(i, j + 1) + fu * d(i + 1, j + 1));
  return inside + std::hypot(u - cu, w - cw) * cell_;
}

std::array<double, 2> PlaneDistance::gradient(double x, double y) const {
  return {(at(x + cell_, y) - at(x - cell_, y)) / (2 * cell_), (at(x, y + cell_) - at(x, y - cell_)) / (2 * cell_)};
}

}  // namespace rockbake
