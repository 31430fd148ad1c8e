#include "sim/distance_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace rockbake {
namespace {

// Voxels of reach the field resolves: centre distances up to reach + ½ voxel.
int bandVoxels(double reach, double h) {
  return int(std::ceil(reach / h)) + 1;
}
// Squared distances at or above the cap read as "beyond the reach".
std::int64_t capFor(double reach, double h) {
  const std::int64_t band = bandVoxels(reach, h);
  return (band + 1) * (band + 1);
}
constexpr std::int64_t kNarrowCap = std::numeric_limits<std::int16_t>::max();

// One line of the separable exact transform (Felzenszwalb & Huttenlocher's
// lower envelope of parabolas): out[q] = min over p of (q - p)² + f[p], over
// the samples with f below `cap` and, where asked, a feature (f = 0) just
// beyond either end; capped at `cap`.
class LineTransform {
 public:
  void run(const std::int32_t* f, int n, bool feature_before, bool feature_after, std::int32_t cap, std::int32_t* out) {
    position_.resize(std::size_t(n) + 2);
    value_.resize(std::size_t(n) + 2);
    start_.resize(std::size_t(n) + 3);
    int k = -1;
    const auto add = [&](int q, std::int32_t fq) {
      double s = -std::numeric_limits<double>::infinity();
      while (k >= 0) {
        const int p = position_[std::size_t(k)];
        s = ((double(fq) + double(q) * q) - (double(value_[std::size_t(k)]) + double(p) * p)) / (2.0 * (q - p));
        if (s > start_[std::size_t(k)]) break;
        --k;
      }
      if (k < 0) s = -std::numeric_limits<double>::infinity();
      ++k;
      position_[std::size_t(k)] = q;
      value_[std::size_t(k)] = fq;
      start_[std::size_t(k)] = s;
    };
    if (feature_before) add(-1, 0);
    for (int q = 0; q < n; ++q)
      if (f[q] < cap) add(q, f[q]);
    if (feature_after) add(n, 0);
    if (k < 0) {
      std::fill(out, out + n, cap);
      return;
    }
    start_[std::size_t(k) + 1] = std::numeric_limits<double>::infinity();
    int j = 0;
    for (int q = 0; q < n; ++q) {
      while (start_[std::size_t(j) + 1] < q) ++j;
      const std::int64_t d = std::int64_t(q - position_[std::size_t(j)]);
      out[q] = std::int32_t(std::min<std::int64_t>(d * d + value_[std::size_t(j)], cap));
    }
  }

 private:
  std::vector<int> position_;
  std::vector<std::int32_t> value_;
  std::vector<double> start_;
};

// Per thread: a line's values and states, and the transform's buffers.
struct LineScratch {
  std::vector<std::int32_t> values, f, out;
  std::vector<std::uint8_t> states;
  LineTransform transform;
};

// A line of squared distances (each to the nearest cell of the other kind
// within the lines already passed) becomes the same over one more axis: for
// each kind, the cells of the other kind are features at 0. Inside cells also
// see the outside beyond the line's ends where asked.
void passLine(LineScratch& s, int n, bool outside_before, bool outside_after, std::int32_t cap) {
  s.f.resize(std::size_t(n));
  s.out.resize(std::size_t(n));
  for (std::uint8_t kind = 0; kind < 2; ++kind) {
    bool any = false;
    for (int q = 0; q < n; ++q) {
      const bool same = s.states[std::size_t(q)] == kind;
      any |= same;
      s.f[std::size_t(q)] = same ? s.values[std::size_t(q)] : 0;
    }
    if (!any) continue;
    s.transform.run(s.f.data(), n, kind == 1 && outside_before, kind == 1 && outside_after, cap, s.out.data());
    for (int q = 0; q < n; ++q)
      if (s.states[std::size_t(q)] == kind) s.values[std::size_t(q)] = s.out[std::size_t(q)];
  }
}

template <typename T>
std::vector<T> squaredDistances(const std::vector<std::uint8_t>& inside, const GridLayout& g, std::int32_t cap) {
  std::vector<T> sq(g.cellCount());
  const std::size_t nx = std::size_t(g.nx), ny = std::size_t(g.ny);
  const auto squared = [cap](std::int64_t d) {
    return std::min<std::int64_t>(std::min<std::int64_t>(d, cap) * std::min<std::int64_t>(d, cap), cap);
  };
  // Along x: the nearest cell of the other kind in the row (the outside
  // continues beyond both ends).
  tbb::parallel_for(0, g.nz, [&](int z) {
    for (int y = 0; y < g.ny; ++y) {
      const std::size_t row = g.index(0, y, z);
      const std::int64_t none = std::int64_t(1) << 40;
      std::int64_t last[2] = {-1, -none};  // last outside, last inside
      for (int x = 0; x < g.nx; ++x) {
        const bool in = inside[row + std::size_t(x)] != 0;
        last[in] = x;
        sq[row + std::size_t(x)] = T(squared(x - last[!in]));
      }
      std::int64_t next[2] = {g.nx, none};
      for (int x = g.nx - 1; x >= 0; --x) {
        const bool in = inside[row + std::size_t(x)] != 0;
        next[in] = x;
        sq[row + std::size_t(x)] = T(std::min<std::int64_t>(squared(next[!in] - x), sq[row + std::size_t(x)]));
      }
    }
  });

  tbb::enumerable_thread_specific<LineScratch> scratch;
  // Along y, a layer at a time.
  tbb::parallel_for(0, g.nz, [&](int z) {
    LineScratch& s = scratch.local();
    s.values.resize(ny);
    s.states.resize(ny);
    for (std::size_t x = 0; x < nx; ++x) {
      const std::size_t first = g.index(int(x), 0, z);
      for (std::size_t y = 0; y < ny; ++y) {
        s.values[y] = sq[first + y * nx];
        s.states[y] = inside[first + y * nx] ? 1 : 0;
      }
      passLine(s, g.ny, true, true, cap);
      for (std::size_t y = 0; y < ny; ++y) sq[first + y * nx] = T(s.values[y]);
    }
  });

  // Along z, a y-plane at a time, its columns copied out row by row to read
  // the grid in order.
  const std::size_t nz = std::size_t(g.nz);
  tbb::enumerable_thread_specific<std::vector<T>> planes;
  tbb::enumerable_thread_specific<std::vector<std::uint8_t>> plane_states;
  tbb::parallel_for(0, g.ny, [&](int y) {
    LineScratch& s = scratch.local();
    std::vector<T>& plane = planes.local();
    std::vector<std::uint8_t>& states = plane_states.local();
    plane.resize(nx * nz);
    states.resize(nx * nz);
    for (std::size_t z = 0; z < nz; ++z) {
      const std::size_t row = g.index(0, y, int(z));
      for (std::size_t x = 0; x < nx; ++x) {
        plane[x * nz + z] = sq[row + x];
        states[x * nz + z] = inside[row + x] ? 1 : 0;
      }
    }
    s.values.resize(nz);
    s.states.resize(nz);
    for (std::size_t x = 0; x < nx; ++x) {
      std::copy_n(plane.begin() + std::ptrdiff_t(x * nz), nz, s.values.begin());
      std::copy_n(states.begin() + std::ptrdiff_t(x * nz), nz, s.states.begin());
      passLine(s, g.nz, !g.ground, true, cap);
      std::copy_n(s.values.begin(), nz, plane.begin() + std::ptrdiff_t(x * nz));
    }
    for (std::size_t z = 0; z < nz; ++z) {
      const std::size_t row = g.index(0, y, int(z));
      for (std::size_t x = 0; x < nx; ++x) sq[row + x] = inside[row + x] ? T(-plane[x * nz + z]) : plane[x * nz + z];
    }
  });
  return sq;
}

}  // namespace

double SignedDistanceField::operator[](std::size_t cell) const {
  const double sq = narrow_.empty() ? double(wide_[cell]) : double(narrow_[cell]);
  const double d = std::min((std::sqrt(std::abs(sq)) - 0.5) * h_, reach_);
  return sq < 0 ? -d : d;
}

SignedDistanceField signedDistance(const std::vector<std::uint8_t>& inside, const GridLayout& g, double reach) {
  const std::int64_t cap = capFor(reach, g.h);
  if (cap <= kNarrowCap) return {squaredDistances<std::int16_t>(inside, g, std::int32_t(cap)), {}, g.h, reach};
  const std::int64_t wide_cap = std::min<std::int64_t>(cap, std::numeric_limits<std::int32_t>::max());
  return {{}, squaredDistances<std::int32_t>(inside, g, std::int32_t(wide_cap)), g.h, reach};
}

std::uint64_t signedDistanceBytes(const GridLayout& g, double reach) {
  const std::uint64_t per_cell = capFor(reach, g.h) <= kNarrowCap ? 2 : 4;
  // The field, and per thread one y-plane of columns with its states.
  const std::uint64_t plane = std::uint64_t(g.nx) * std::uint64_t(g.nz) * (per_cell + 1);
  return g.cellCount() * per_cell + 2 * plane;
}

}  // namespace rockbake
