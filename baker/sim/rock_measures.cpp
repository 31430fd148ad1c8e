#include "sim/rock_measures.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <Eigen/Eigenvalues>

namespace rockbake {
namespace {

// A rock's voxels on their own lattice, positions relative to the rock's
// anchor: its footprint centroid, at the centre height of its lowest voxel.
struct Occupancy {
  int lo[3]{}, n[3]{};  // lattice cells lo .. lo + n − 1 of the layout
  double h = 1.0;
  Vec3d origin{};  // anchor-relative position of cell lo's centre
  std::vector<std::uint8_t> cells;
  std::size_t count = 0;

  bool at(const Vec3d& p) const {
    int c[3];
    for (std::size_t a = 0; a < 3; ++a) {
      c[a] = int(std::lround((p[a] - origin[a]) / h));
      if (c[a] < 0 || c[a] >= n[a]) return false;
    }
    return cells[std::size_t(c[0]) + std::size_t(n[0]) * (std::size_t(c[1]) + std::size_t(n[1]) * std::size_t(c[2]))];
  }
};

Occupancy occupancy(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  Occupancy o;
  o.h = g.h;
  int lo[3] = {g.nx, g.ny, g.nz}, hi[3] = {-1, -1, -1};
  double sx = 0, sy = 0;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] == Material::Rock) {
          const int c[3] = {x, y, z};
          for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
          sx += x, sy += y;
          ++o.count;
        }
  if (o.count == 0) return o;
  for (int a = 0; a < 3; ++a) o.lo[a] = lo[a], o.n[a] = hi[a] - lo[a] + 1;
  const Vec3d anchor{g.origin[0] + (sx / double(o.count) + 0.5) * g.h, g.origin[1] + (sy / double(o.count) + 0.5) * g.h,
                     g.center(0, 0, lo[2])[2]};
  o.origin = sub(g.center(lo[0], lo[1], lo[2]), anchor);
  o.cells.assign(std::size_t(o.n[0]) * std::size_t(o.n[1]) * std::size_t(o.n[2]), 0);
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x)
        if (rock.material[g.index(x, y, z)] == Material::Rock)
          o.cells[std::size_t(x - lo[0]) +
                  std::size_t(o.n[0]) * (std::size_t(y - lo[1]) + std::size_t(o.n[1]) * std::size_t(z - lo[2]))] = 1;
  return o;
}

// IoU of `a` and `b` posed: b's point q is at R(turn) · M · k q, where M mirrors x.
double posedIoU(const Occupancy& a, const Occupancy& b, double k, double turn, bool mirror) {
  const double c = std::cos(turn), s = std::sin(turn);
  // The posed b's bounding box, from its lattice's corners.
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (int corner = 0; corner < 8; ++corner) {
    Vec3d q;
    for (std::size_t ax = 0; ax < 3; ++ax)
      q[ax] = b.origin[ax] + ((corner >> ax) & 1 ? double(b.n[ax] - 1) + 0.5 : -0.5) * b.h;
    q = scale(q, k);
    if (mirror) q[0] = -q[0];
    const Vec3d p{c * q[0] - s * q[1], s * q[0] + c * q[1], q[2]};
    for (std::size_t ax = 0; ax < 3; ++ax) lo[ax] = std::min(lo[ax], p[ax]), hi[ax] = std::max(hi[ax], p[ax]);
  }
  // Walk a's lattice over that box: a cell is in posed b when its centre maps into a voxel of b.
  int from[3], to[3];
  for (std::size_t ax = 0; ax < 3; ++ax) {
    from[ax] = int(std::floor((lo[ax] - a.origin[ax]) / a.h));
    to[ax] = int(std::ceil((hi[ax] - a.origin[ax]) / a.h));
  }
  struct Counts {
    std::size_t both = 0, posed = 0;
  };
  const Counts counts = tbb::parallel_reduce(
      tbb::blocked_range<int>(from[2], to[2] + 1), Counts{},
      [&](const tbb::blocked_range<int>& zs, Counts acc) {
        for (int z = zs.begin(); z != zs.end(); ++z)
          for (int y = from[1]; y <= to[1]; ++y)
            for (int x = from[0]; x <= to[0]; ++x) {
              const Vec3d p{a.origin[0] + x * a.h, a.origin[1] + y * a.h, a.origin[2] + z * a.h};
              Vec3d q{(c * p[0] + s * p[1]) / k, (-s * p[0] + c * p[1]) / k, p[2] / k};
              if (mirror) q[0] = -q[0];
              if (!b.at(q)) continue;
              ++acc.posed;
              if (a.at(p)) ++acc.both;
            }
        return acc;
      },
      [](Counts l, const Counts& r) {
        l.both += r.both, l.posed += r.posed;
        return l;
      });
  const double uni = double(a.count + counts.posed - counts.both);
  return uni > 0 ? double(counts.both) / uni : 0.0;
}

}  // namespace

double alignedIoU(const VoxelRock& rock_a, const VoxelRock& rock_b) {
  const Occupancy a = occupancy(rock_a), b = occupancy(rock_b);
  if (a.count == 0 || b.count == 0) return 0.0;
  const double k = std::cbrt(double(a.count) * std::pow(a.h, 3) / (double(b.count) * std::pow(b.h, 3)));
  double best = 0.0;
  for (int mirror = 0; mirror < 2; ++mirror)
    for (int step = 0; step < 36; ++step)
      best = std::max(best, posedIoU(a, b, k, step * 10.0 * std::numbers::pi / 180.0, mirror == 1));
  return best;
}

std::array<double, 3> principalAxes(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  std::size_t count = 0;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] == Material::Rock) {
          const Vec3d p = g.center(x, y, z);
          const Eigen::Vector3d v(p[0], p[1], p[2]);
          sum += v, outer += v * v.transpose();
          ++count;
        }
  if (count == 0) return {0.0, 0.0, 0.0};
  const Eigen::Vector3d mean = sum / double(count);
  const Eigen::Matrix3d covariance = outer / double(count) - mean * mean.transpose();
  const Eigen::Vector3d eigen = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues();  // ascending
  return {std::sqrt(std::max(0.0, eigen[2])), std::sqrt(std::max(0.0, eigen[1])), std::sqrt(std::max(0.0, eigen[0]))};
}

}  // namespace rockbake
