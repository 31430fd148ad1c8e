#include "collision/air_count.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rockbake {

AirCounter::AirCounter(const VoxelRock& rock, const VoxelBounds& box) : lo_(box.lo) {
  for (int a = 0; a < 3; ++a) size_[a] = box.hi[a] - box.lo[a];
  if (size_[0] >= 0xFFFF) throw std::invalid_argument("AirCounter: rows longer than 16-bit counts reach");
  const std::size_t stride = std::size_t(size_[0]) + 1;
  prefix_.assign(stride * std::size_t(size_[1]) * std::size_t(size_[2]), 0);
  const GridLayout& g = rock.layout;
  for (int z = 0; z < size_[2]; ++z)
    for (int y = 0; y < size_[1]; ++y) {
      std::uint16_t* row = &prefix_[stride * (std::size_t(y) + std::size_t(size_[1]) * std::size_t(z))];
      const Material* cells = &rock.material[g.index(lo_[0], lo_[1] + y, lo_[2] + z)];
      for (int x = 0; x < size_[0]; ++x) row[x + 1] = std::uint16_t(row[x] + (cells[x] == Material::Air));
    }
}

std::size_t AirCounter::count(const std::vector<HullPlane>& planes, const Vec3d& lo, const Vec3d& hi) const {
  constexpr double kOn = 1e-9;  // a centre this close to a face counts as on it
  // Rows whose centres lie in [lo, hi], clipped to the box.
  const auto first = [&](int a) { return std::max(0, int(std::ceil(lo[a] - 0.5 - kOn)) - lo_[a]); };
  const auto last = [&](int a) { return std::min(size_[a] - 1, int(std::floor(hi[a] - 0.5 + kOn)) - lo_[a]); };
  const int y0 = first(1), y1 = last(1), z0 = first(2), z1 = last(2);
  const double x_lo = lo[0], x_hi = hi[0];
  const std::size_t stride = std::size_t(size_[0]) + 1;
  std::size_t air = 0;
  for (int z = z0; z <= z1; ++z)
    for (int y = y0; y <= y1; ++y) {
      // The row's line x ↦ (x, y + ½, z + ½) inside every half-space.
      const double cy = lo_[1] + y + 0.5, cz = lo_[2] + z + 0.5;
      double from = x_lo, to = x_hi;
      for (const HullPlane& p : planes) {
        const double rest = p.offset - p.normal[1] * cy - p.normal[2] * cz;
        if (p.normal[0] > 1e-12)
          to = std::min(to, rest / p.normal[0]);
        else if (p.normal[0] < -1e-12)
          from = std::max(from, rest / p.normal[0]);
        else if (rest < -kOn)
          from = to + 1;  // the row misses this half-space
        if (from > to + kOn) break;
      }
      // Cells whose centres i + ½ lie in [from, to].
      const int i0 = std::max(0, int(std::ceil(from - 0.5 - kOn)) - lo_[0]);
      const int i1 = std::min(size_[0] - 1, int(std::floor(to - 0.5 + kOn)) - lo_[0]);
      if (i0 > i1) continue;
      const std::uint16_t* row = &prefix_[stride * (std::size_t(y) + std::size_t(size_[1]) * std::size_t(z))];
      air += std::size_t(row[i1 + 1] - row[i0]);
    }
  return air;
}

}  // namespace rockbake
