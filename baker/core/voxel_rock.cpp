#include "core/voxel_rock.h"

#include <stdexcept>
#include <algorithm>

namespace rockbake {

void RowSpans::cover(std::size_t row, int x_lo, int x_hi) {
  std::vector<float>& v = values[row];
  std::int32_t& x0 = first[row];
  if (v.empty()) {
    x0 = x_lo;
    v.assign(std::size_t(x_hi - x_lo + 1), fill);
    v.shrink_to_fit();
    return;
  }
  const int lo = std::min(x_lo, int(x0)), hi = std::max(x_hi, int(x0) + int(v.size()) - 1);
  if (lo == x0 && hi == x0 + int(v.size()) - 1) return;
  std::vector<float> grown(std::size_t(hi - lo + 1), fill);
  std::copy(v.begin(), v.end(), grown.begin() + (x0 - lo));
  v = std::move(grown);
  x0 = lo;
}

void RowSpans::set(std::size_t row, int x, float value) {
  if (!covers(row, x)) {
    if (value == fill) return;
    cover(row, x, x);
  }
  slot(row, x) = value;
}

std::vector<float> RowSpans::toDense() const {
  std::vector<float> dense(std::size_t(nx) * first.size(), fill);
  for (std::size_t row = 0; row < first.size(); ++row)
    std::copy(values[row].begin(), values[row].end(),
              dense.begin() + std::ptrdiff_t(row * std::size_t(nx) + first[row]));
  return dense;
}

std::size_t RowSpans::storedCells() const {
  std::size_t n = 0;
  for (const auto& v : values) n += v.size();
  return n;
}

void resetRockValues(VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  rock.integrity = RowSpans(g, 1.f);
  rock.durability = RowSpans(g, 0.f);
  for (std::size_t row = 0; row < std::size_t(g.ny) * std::size_t(g.nz); ++row) {
    const Material* m = rock.material.data() + row * std::size_t(g.nx);
    int lo = g.nx, hi = -1;
    for (int x = 0; x < g.nx; ++x)
      if (m[x] == Material::Rock) lo = std::min(lo, x), hi = x;
    if (hi < 0) continue;
    rock.integrity.cover(row, lo, hi);
    rock.durability.cover(row, lo, hi);
  }
}

std::size_t VoxelRock::count(Material m) const {
  return std::size_t(std::count(material.begin(), material.end(), m));
}

double rockIntersectionOverUnion(const VoxelRock& a, const VoxelRock& b) {
  if (a.material.size() != b.material.size())
    throw std::invalid_argument("rockIntersectionOverUnion: the rocks lie on different layouts");
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i < a.material.size(); ++i) {
    const bool ra = a.material[i] == Material::Rock, rb = b.material[i] == Material::Rock;
    both += ra && rb;
    either += ra || rb;
  }
  return either ? double(both) / double(either) : 1.0;
}

}  // namespace rockbake
