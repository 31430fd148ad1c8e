#include "clasts/place_clasts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/hash.h"
#include "core/vec3.h"

namespace rockbake {
namespace {

using Quat = std::array<double, 4>;  // x, y, z, w

Quat multiply(const Quat& a, const Quat& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1], a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3], a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

Quat aboutAxis(const Vec3d& unit_axis, double radians) {
  const double s = std::sin(0.5 * radians);
  return {unit_axis[0] * s, unit_axis[1] * s, unit_axis[2] * s, std::cos(0.5 * radians)};
}

// The apron's and the ground's top surface about the pivot, sampled every quarter voxel: the highest
// point of LOD0's colluvium surface above each sample, the ground where there is none.
class ApronHeight {
 public:
  ApronHeight(const GridLayout& g, const Vec3d& pivot, const SurfaceMesh* colluvium)
      : q_(0.25 * g.h), x0_(g.origin[0] - pivot[0]), y0_(g.origin[1] - pivot[1]), nx_(4 * g.nx), ny_(4 * g.ny) {
    const double ground = g.origin[2] - pivot[2];
    z_.assign(std::size_t(nx_) * std::size_t(ny_), ground);
    if (colluvium)
      for (const auto& t : colluvium->triangles) raster(colluvium->positions, t);
  }

  bool inside(double x, double y) const {
    const double u = (x - x0_) / q_ - 0.5, v = (y - y0_) / q_ - 0.5;
    return u >= 0 && v >= 0 && u <= nx_ - 1 && v <= ny_ - 1;
  }
  // Bilinear between the samples; requires inside(x, y).
  double at(double x, double y) const {
    const double u = (x - x0_) / q_ - 0.5, v = (y - y0_) / q_ - 0.5;
    const int i = std::min(int(u), nx_ - 2), j = std::min(int(v), ny_ - 2);
    const double fu = u - i, fv = v - j;
    const auto z = [&](int a, int b) { return z_[std::size_t(a) + std::size_t(nx_) * std::size_t(b)]; };
    return (1 - fv) * ((1 - fu) * z(i, j) + fu * z(i + 1, j)) + fv * ((1 - fu) * z(i, j + 1) + fu * z(i + 1, j + 1));
  }

 private:
  void raster(const std::vector<std::array<float, 3>>& p, const std::array<std::uint32_t, 3>& t) {
    const auto& a = p[t[0]];
    const auto& b = p[t[1]];
    const auto& c = p[t[2]];
    const double area = (double(b[0]) - a[0]) * (double(c[1]) - a[1]) - (double(c[0]) - a[0]) * (double(b[1]) - a[1]);
    if (std::abs(area) < 1e-12) return;
    const auto cell = [&](double w, double w0) { return (w - w0) / q_ - 0.5; };
    const int i0 = std::max(0, int(std::ceil(cell(std::min({a[0], b[0], c[0]}), x0_))));
    const int i1 = std::min(nx_ - 1, int(std::floor(cell(std::max({a[0], b[0], c[0]}), x0_))));
    const int j0 = std::max(0, int(std::ceil(cell(std::min({a[1], b[1], c[1]}), y0_))));
    const int j1 = std::min(ny_ - 1, int(std::floor(cell(std::max({a[1], b[1], c[1]}), y0_))));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double x = x0_ + (i + 0.5) * q_, y = y0_ + (j + 0.5) * q_;
        const double wa = ((double(b[0]) - x) * (double(c[1]) - y) - (double(c[0]) - x) * (double(b[1]) - y)) / area;
        const double wb = ((double(c[0]) - x) * (double(a[1]) - y) - (double(a[0]) - x) * (double(c[1]) - y)) / area;
        const double wc = 1.0 - wa - wb;
        if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
        double& z = z_[std::size_t(i) + std::size_t(nx_) * std::size_t(j)];
        z = std::max(z, wa * a[2] + wb * b[2] + wc * c[2]);
      }
  }

  double q_, x0_, y0_;
  int nx_, ny_;
  std::vector<double> z_;
};

// Per voxel column: whether it holds rock, or lies beside one that does (a stone keeps off it),
// and whether its top is colluvium.
struct Columns {
  int nx = 0, ny = 0;
  std::vector<std::uint8_t> rock, near_rock, apron;
  std::vector<std::array<int, 2>> rock_edge;  // rock columns beside one without rock

  explicit Columns(const VoxelRock& r) : nx(r.layout.nx), ny(r.layout.ny) {
    const GridLayout& g = r.layout;
    const std::size_t n = std::size_t(nx) * std::size_t(ny);
    rock.assign(n, 0), near_rock.assign(n, 0), apron.assign(n, 0);
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        for (int z = g.nz - 1; z >= 0; --z) {
          const Material m = r.material[g.index(x, y, z)];
          if (m == Material::Rock) rock[at(x, y)] = 1;
          if (m == Material::Colluvium && !rock[at(x, y)]) apron[at(x, y)] = 1;
        }
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        bool edge = false;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int u = x + dx, v = y + dy;
            const bool r_uv = u >= 0 && v >= 0 && u < nx && v < ny && rock[at(u, v)];
            if (r_uv) near_rock[at(x, y)] = 1;
            if (rock[at(x, y)] && !r_uv) edge = true;
          }
        if (edge) rock_edge.push_back({x, y});
      }
  }
  std::size_t at(int x, int y) const { return std::size_t(x) + std::size_t(nx) * std::size_t(y); }
};

struct Site {
  double x, y;           // column centre about the pivot
  double foot_distance;  // world units
};

// Columns a stone may be sent to: the apron's, and the ground's within two voxels of it (the
// largest stones roll past the toe), sorted by their distance from the rock's foot.
std::vector<Site> sites(const Columns& cols, const GridLayout& g, const Vec3d& pivot) {
  std::vector<Site> out;
  for (int y = 0; y < cols.ny; ++y)
    for (int x = 0; x < cols.nx; ++x) {
      if (cols.near_rock[cols.at(x, y)]) continue;
      bool beside_apron = false;
      for (int dy = -2; dy <= 2 && !beside_apron; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < cols.nx && v < cols.ny && cols.apron[cols.at(u, v)]) beside_apron = true;
        }
      if (!beside_apron) continue;
      double d2 = std::numeric_limits<double>::max();
      for (const auto& e : cols.rock_edge)
        d2 = std::min(d2, double(e[0] - x) * (e[0] - x) + double(e[1] - y) * (e[1] - y));
      const Vec3d c = g.center(x, y, 0);
      out.push_back({c[0] - pivot[0], c[1] - pivot[1], std::sqrt(d2) * g.h});
    }
  std::stable_sort(out.begin(), out.end(),
                   [](const Site& a, const Site& b) { return a.foot_distance < b.foot_distance; });
  return out;
}

// Sizes (world units) from the truncated power law, largest first.
std::vector<double> drawSizes(const ClastParams& p, double h, std::uint64_t seed) {
  const double lo = p.size[0] * h, hi = p.size[1] * h, a = p.size_exponent;
  const double tail = std::pow(lo / hi, a);
  std::vector<double> sizes(std::size_t(p.count));
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const double u = unitInterval(counterHash(seed, purposeId("clast size"), i, 0));
    sizes[i] = lo / std::pow(1.0 - u * (1.0 - tail), 1.0 / a);
  }
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  return sizes;
}

double shapeRadius(const SurfaceMesh& m) {
  double r2 = 0;
  for (const auto& v : m.positions) r2 = std::max(r2, double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
  return std::sqrt(r2);
}

// A stone of `size` at (x, y), turned to rest on the surface; false when it leaves the grid or
// comes near the rock, or its lowest point would stand off the surface.
bool rest(ClastInstance& s, const SurfaceMesh& shape, const ApronHeight& height, const Columns& cols,
          const GridLayout& g, const Vec3d& pivot, double yaw_jitter) {
  const double x = s.translation[0], y = s.translation[1];
  const double d = std::max(0.5 * g.h, 0.5 * s.scale);
  if (!height.inside(x - d, y - d) || !height.inside(x + d, y + d)) return false;
  const double gx = (height.at(x + d, y) - height.at(x - d, y)) / (2 * d);
  const double gy = (height.at(x, y + d) - height.at(x, y - d)) / (2 * d);
  const Vec3d up = normalised(Vec3d{-gx, -gy, 1.0}, Vec3d{0, 0, 1});
  // The long axis down the slope, give or take; on the flat, any way.
  const double slope = std::hypot(gx, gy);
  const double downhill = slope > 1e-3 ? std::atan2(-gy, -gx) : 0.0;
  const Quat yaw = aboutAxis({0, 0, 1}, downhill + yaw_jitter);
  const Vec3d axis = cross(Vec3d{0, 0, 1}, up);
  const double tilt = std::asin(std::min(1.0, length(axis)));
  const Quat lean = tilt > 1e-9 ? aboutAxis(normalised(axis, Vec3d{1, 0, 0}), tilt) : Quat{0, 0, 0, 1};
  s.rotation = multiply(lean, yaw);
  double lift = std::numeric_limits<double>::lowest();
  double lowest = std::numeric_limits<double>::max(), lowest_ground = 0;
  for (const auto& v : shape.positions) {
    const Vec3d w = clastVertex(s, v);  // s.translation is (x, y, 0) until it rests
    const double px = w[0], py = w[1];
    if (!height.inside(px, py)) return false;
    const int cx = int(std::floor((px + pivot[0] - g.origin[0]) / g.h));
    const int cy = int(std::floor((py + pivot[1] - g.origin[1]) / g.h));
    if (cx < 0 || cy < 0 || cx >= g.nx || cy >= g.ny || cols.near_rock[cols.at(cx, cy)]) return false;
    const double under = height.at(px, py);
    lift = std::max(lift, under - w[2]);
    if (w[2] < lowest) lowest = w[2], lowest_ground = under;
  }
  const double bed = 0.1 * g.h;  // bedded in, not balanced on a point
  s.translation[2] = lift - bed;
  return s.translation[2] + lowest - lowest_ground <= 0.15 * g.h;
}

}  // namespace

std::vector<ClastInstance> placeClasts(const ClastPlacement& in) {
  const VoxelRock& rock = *in.rock;
  const GridLayout& g = rock.layout;
  const std::vector<SurfaceMesh>& shapes = *in.shapes;
  if (!g.ground || shapes.empty() || !in.colluvium || in.colluvium->triangles.empty()) return {};
  const Columns cols(rock);
  const std::vector<Site> site = sites(cols, g, in.pivot);
  if (site.empty()) return {};
  const ApronHeight height(g, in.pivot, in.colluvium);
  std::vector<double> radius;
  for (const SurfaceMesh& m : shapes) radius.push_back(shapeRadius(m));

  const std::vector<double> sizes = drawSizes(in.params, g.h, in.seed);
  const std::uint64_t purpose = purposeId("clast site");
  std::vector<ClastInstance> placed;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const double rank = sizes.size() > 1 ? double(i) / double(sizes.size() - 1) : 0.0;  // 0: the largest
    for (int attempt = 0; attempt < kClastTries; ++attempt) {
      const auto draw = [&](int what) { return unitInterval(counterHash(in.seed, purpose, i, attempt * 8 + what)); };
      // Fall sorting: the larger, the further out, with chance's share (and a wider search each try).
      const double spread = 0.1 * attempt / kClastTries;
      const double t = std::clamp(0.55 * (1.0 - rank) + 0.45 * draw(0) + spread * (draw(1) - 0.5), 0.0, 1.0);
      const Site& at = site[std::size_t(std::lround(t * double(site.size() - 1)))];
      ClastInstance s;
      s.shape = std::min(int(draw(2) * double(shapes.size())), int(shapes.size()) - 1);
      s.scale = sizes[i];
      s.translation = {at.x + (draw(3) - 0.5) * g.h, at.y + (draw(4) - 0.5) * g.h, 0.0};
      s.foot_distance = at.foot_distance;
      if (!rest(s, shapes[std::size_t(s.shape)], height, cols, g, in.pivot, (draw(5) - 0.5) * 1.4)) continue;
      const double r = s.scale * radius[std::size_t(s.shape)];
      const bool overlaps = std::any_of(placed.begin(), placed.end(), [&](const ClastInstance& o) {
        const double ro = o.scale * radius[std::size_t(o.shape)];
        return length(sub(s.translation, o.translation)) < 0.9 * (r + ro);
      });
      if (overlaps) continue;
      placed.push_back(s);
      break;
    }
  }
  return placed;
}

}  // namespace rockbake
