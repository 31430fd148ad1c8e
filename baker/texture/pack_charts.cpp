#include "texture/pack_charts.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

namespace rockbake {
namespace {

using UV = std::array<double, 2>;

constexpr int kRounds = 8;  // rounds of packing that search the density

double cross(const UV& o, const UV& a, const UV& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Andrew's monotone chain, counter-clockwise.
std::vector<UV> convexHull(std::vector<UV> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<UV> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// The chart turned so that its bounding rectangle is smallest and wider than tall, moved to
// the origin: a rotation (cos, sin) and the rotated chart's lower corner.
struct Placement {
  double cos = 1, sin = 0;
  UV low{0, 0};
  double width = 0, height = 0;

  UV apply(const UV& p) const { return {cos * p[0] - sin * p[1] - low[0], sin * p[0] + cos * p[1] - low[1]}; }
  // The same chart turned a further quarter turn, (x, y) → (−y, x).
  Placement quarterTurn() const { return {-sin, cos, {-(low[1] + height), low[0]}, height, width}; }
};

Placement orient(const std::vector<UV>& uv) {
  const std::vector<UV> hull = convexHull(uv);
  Placement best;
  double best_area = std::numeric_limits<double>::infinity();
  const auto tryAngle = [&](double c, double s) {
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const UV& p : hull) {
      const double x = c * p[0] - s * p[1], y = s * p[0] + c * p[1];
      lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x);
      lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
    }
    const double area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
    if (area < best_area * (1 - 1e-9)) {
      best_area = area;
      best = {c, s, {lo[0], lo[1]}, hi[0] - lo[0], hi[1] - lo[1]};
    }
  };
  tryAngle(1, 0);
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const UV& a = hull[i];
    const UV& b = hull[(i + 1) % hull.size()];
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (len > 0) tryAngle((b[0] - a[0]) / len, -(b[1] - a[1]) / len);  // turns the edge onto +x
  }
  return best.height > best.width ? best.quarterTurn() : best;
}

// A chart's footprint at one density: per column of texels, the runs of rows its triangles touch
// (ascending, apart), grown by `grow` texels each way (a chessboard dilation), with the chart
// itself `grow` texels in from the footprint's lower corner.
struct Run {
  int from = 0, to = 0;  // rows [from, to)
};

struct Footprint {
  int width = 0, height = 0;
  std::vector<std::vector<Run>> columns;
};

// Sorts runs and merges those that overlap or touch.
void mergeRuns(std::vector<Run>& runs) {
  std::sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) { return a.from < b.from; });
  std::size_t n = 0;
  for (const Run& r : runs)
    if (n > 0 && r.from <= runs[n - 1].to)
      runs[n - 1].to = std::max(runs[n - 1].to, r.to);
    else
      runs[n++] = r;
  runs.resize(n);
}

Footprint footprint(const PackChart& chart, const Placement& place, double density, int grow) {
  const int width = int(std::ceil(density * place.width)) + 1, height = int(std::ceil(density * place.height)) + 1;
  std::vector<std::vector<Run>> touched(static_cast<std::size_t>(width));
  std::vector<UV> p(chart.uv.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const UV q = place.apply(chart.uv[i]);
    p[i] = {density * q[0], density * q[1]};
  }
  // Conservative: a texel square meets the triangle where its centre lies in the triangle
  // grown by the square (each edge pushed out by half the square's extent along its normal).
  for (const auto& t : chart.triangles) {
    const UV &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    const int x0 = std::max(0, int(std::floor(std::min({a[0], b[0], c[0]})))),
              x1 = std::min(width - 1, int(std::floor(std::max({a[0], b[0], c[0]}))));
    const int y0 = std::max(0, int(std::floor(std::min({a[1], b[1], c[1]})))),
              y1 = std::min(height - 1, int(std::floor(std::max({a[1], b[1], c[1]}))));
    const double sign = cross(a, b, c) < 0 ? -1.0 : 1.0;
    const UV* v[3] = {&a, &b, &c};
    double nx[3], ny[3], off[3];
    for (int k = 0; k < 3; ++k) {
      const UV &s = *v[k], &e = *v[(k + 1) % 3];
      nx[k] = -sign * (e[1] - s[1]), ny[k] = sign * (e[0] - s[0]);  // inward
      off[k] = 0.5 * (std::abs(nx[k]) + std::abs(ny[k])) - (nx[k] * s[0] + ny[k] * s[1]);
    }
    const auto inside = [&](int x, int y) {
      for (int k = 0; k < 3; ++k)
        if (nx[k] * (x + 0.5) + ny[k] * (y + 0.5) + off[k] < 0) return false;
      return true;
    };
    for (int x = x0; x <= x1; ++x) {
      int y = y0;  // the column's first and last touched texel: a convex shape's are contiguous
      while (y <= y1 && !inside(x, y)) ++y;
      if (y > y1) continue;
      int z = y1;
      while (z > y && !inside(x, z)) --z;
      touched[std::size_t(x)].push_back({y, z + 1});
    }
  }
  Footprint f;
  f.width = width + 2 * grow;
  f.height = height + 2 * grow;
  f.columns.resize(std::size_t(f.width));
  for (int x = 0; x < width; ++x) {
    mergeRuns(touched[std::size_t(x)]);
    for (int d = 0; d <= 2 * grow; ++d)  // column x lands at x + grow; grown, it reaches x … x + 2 · grow
      for (const Run& r : touched[std::size_t(x)]) f.columns[std::size_t(x + d)].push_back({r.from, r.to + 2 * grow});
  }
  for (auto& runs : f.columns) mergeRuns(runs);
  return f;
}

// The same footprint turned half a turn (about its own centre).
Footprint halfTurn(const Footprint& f) {
  Footprint r = f;
  for (int x = 0; x < f.width; ++x) {
    const auto& from = f.columns[std::size_t(f.width - 1 - x)];
    auto& to = r.columns[std::size_t(x)];
    to.clear();
    for (auto run = from.rbegin(); run != from.rend(); ++run) to.push_back({f.height - run->to, f.height - run->from});
  }
  return r;
}

struct Spot {
  int x = 0, y = 0, turn = 0;
};

// The texels packed so far, per column a bitset of rows (1: taken by a grown footprint), rows
// 0 … 4 · size − 1: packings taller than the map are measured too, to rescale the density.
class Occupancy {
 public:
  Occupancy(int columns, int rows)
      : words_((rows + 63) / 64),
        rows_(rows),
        bits_(std::size_t(columns) * words_, 0),
        floor_(std::size_t(columns), 0) {}

  int rows() const { return rows_; }
  // Column x's lowest free row: no texel of a footprint there can sit lower.
  int floor(int x) const { return floor_[std::size_t(x)]; }

  // The first taken row of column x in [from, to), or −1.
  int firstTaken(int x, int from, int to) const {
    const std::uint64_t* col = &bits_[std::size_t(x) * words_];
    for (int w = from >> 6; w << 6 < to; ++w) {
      std::uint64_t bits = col[w];
      if (w == from >> 6) bits &= ~std::uint64_t(0) << (from & 63);
      if (bits == 0) continue;
      const int r = (w << 6) + std::countr_zero(bits);
      return r < to ? r : -1;
    }
    return -1;
  }

  // The first free row of column x at or above `from` (rows_ when there is none).
  int firstFree(int x, int from) const {
    const std::uint64_t* col = &bits_[std::size_t(x) * words_];
    for (int w = from >> 6; w < int(words_); ++w) {
      std::uint64_t bits = ~col[w];
      if (w == from >> 6) bits &= ~std::uint64_t(0) << (from & 63);
      if (bits != 0) return std::min(rows_, (w << 6) + std::countr_zero(bits));
    }
    return rows_;
  }

  void take(int x, int from, int to) {
    std::uint64_t* col = &bits_[std::size_t(x) * words_];
    for (int r = from; r < to; ++r) col[r >> 6] |= std::uint64_t(1) << (r & 63);
    floor_[std::size_t(x)] = firstFree(x, floor_[std::size_t(x)]);
  }

 private:
  std::size_t words_;
  int rows_;
  std::vector<std::uint64_t> bits_;
  std::vector<int> floor_;
};

// The lowest row at which a footprint with its first column at x meets no taken texel (below
// the packing's top, into any hole large enough, as well as on it), or nothing when that is
// higher than `above` (the best found so far) or than the rows held. Each taken texel in the
// way lifts the footprint to just past the run it belongs to, until none is in the way.
bool lowestFree(const Footprint& f, const Occupancy& taken, int x, int above, int& y) {
  y = 0;  // start where each column's lowest run meets that column's lowest free row
  for (int i = 0; i < f.width; ++i)
    if (!f.columns[std::size_t(i)].empty())
      y = std::max(y, taken.floor(x + i) - f.columns[std::size_t(i)].front().from);
  if (y > above) return false;
  for (bool lifted = true; lifted;) {
    lifted = false;
    for (int i = 0; i < f.width; ++i)
      for (const Run& run : f.columns[std::size_t(i)]) {
        if (y + run.to > taken.rows()) return false;
        const int r = taken.firstTaken(x + i, y + run.from, y + run.to);
        if (r < 0) continue;
        y = taken.firstFree(x + i, r) - run.from;
        if (y > above) return false;
        lifted = true;
      }
  }
  return true;
}

// Every chart placed, biggest first, where it rests lowest in what is packed so far (holes
// left beneath earlier charts included; ties: further left, then unturned): every kStride-th
// column first, then each column near the best of those. Returns the packing's height, or more
// than `size` when a chart is wider than the map or the packing outgrows the map (it stops
// there: `placed` gives the share of the footprints' texels placed by then, 1 when all fit).
int drop(const std::vector<std::array<Footprint, 4>>& prints, const std::vector<std::size_t>& order, int size,
         std::vector<Spot>& spots, double& placed) {
  constexpr int kStride = 8;
  Occupancy taken(size, 4 * size);
  int height = 0;
  double placed_texels = 0, texels = 0;
  for (const auto& p : prints)
    for (const auto& runs : p[0].columns)
      for (const Run& run : runs) texels += run.to - run.from;
  spots.assign(prints.size(), Spot{});
  for (std::size_t c : order) {
    int best_y = std::numeric_limits<int>::max();
    Spot best{-1, 0, 0};
    const auto consider = [&](int turn, int x) {
      int y = 0;
      if (!lowestFree(prints[c][std::size_t(turn)], taken, x, best_y - 1, y)) return;
      best_y = y, best = {x, y, turn};
    };
    for (int turn = 0; turn < 4; ++turn) {
      const int last = size - prints[c][std::size_t(turn)].width;
      for (int x = 0; x <= last; x += kStride) consider(turn, x);
      if (last >= 0 && last % kStride != 0) consider(turn, last);
    }
    if (best.x < 0) {
      placed = 0;  // wider than the map: shrink as far as a round may
      return std::numeric_limits<int>::max();
    }
    const Spot coarse = best;
    const int last = size - prints[c][std::size_t(coarse.turn)].width;
    for (int x = std::max(0, coarse.x - kStride + 1); x <= std::min(last, coarse.x + kStride - 1); ++x)
      if (x != coarse.x) consider(coarse.turn, x);
    const Footprint& f = prints[c][std::size_t(best.turn)];
    for (int i = 0; i < f.width; ++i)
      for (const Run& run : f.columns[std::size_t(i)]) {
        taken.take(best.x + i, best.y + run.from, best.y + run.to);
        height = std::max(height, best.y + run.to);
      }
    spots[c] = best;
    for (const auto& runs : f.columns)
      for (const Run& run : runs) placed_texels += run.to - run.from;
    if (height > size) break;
  }
  placed = texels > 0 ? placed_texels / texels : 1.0;
  return height;
}

}  // namespace

double packCharts(std::vector<PackChart>& charts, int size, int padding) {
  if (charts.empty()) return 0.0;
  const int grow = (padding + 1) / 2;  // two grown footprints apart: 2 · grow + 1 > padding texels between charts
  std::vector<Placement> place(charts.size());
  double area = 0;
  for (std::size_t i = 0; i < charts.size(); ++i) {
    place[i] = orient(charts[i].uv);
    for (const auto& t : charts[i].triangles)
      area += 0.5 * std::abs(cross(charts[i].uv[t[0]], charts[i].uv[t[1]], charts[i].uv[t[2]]));
  }
  std::vector<std::size_t> order(charts.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return place[a].width * place[a].height > place[b].width * place[b].height;
  });

  // Start where the charts would cover 60 % of the map, rescale by the height missed until
  // one density fits and one does not, then bisect between them.
  double density = area > 0 ? size * std::sqrt(0.6 / area) : 1.0, fits = 0, fails = 0;
  std::vector<Spot> spots, best_spots;
  std::vector<std::array<Footprint, 4>> prints(charts.size()), best_prints;
  for (int round = 0; round < kRounds || fits == 0; ++round) {
    if (round > 4 * kRounds)
      throw std::runtime_error("cannot pack " + std::to_string(charts.size()) + " UV charts into a " +
                               std::to_string(size) + "² map with " + std::to_string(padding) +
                               "-texel gutters (raise texture.size or lower texture.padding)");
    tbb::parallel_for(std::size_t(0), charts.size(), [&](std::size_t i) {
      prints[i][0] = footprint(charts[i], place[i], density, grow);
      prints[i][1] = halfTurn(prints[i][0]);
      prints[i][2] = footprint(charts[i], place[i].quarterTurn(), density, grow);
      prints[i][3] = halfTurn(prints[i][2]);
    });
    double placed = 1;
    const int height = drop(prints, order, size, spots, placed);
    if (height <= size) {
      fits = density;
      best_spots = spots;
      best_prints = prints;
      if (height >= 0.98 * size) break;  // within 1 % of the density that fills the map
    } else {
      fails = density;
    }
    if (fits > 0 && fails > 0)
      density = std::sqrt(fits * fails);
    else  // heights, and the texels a packing too tall for the map placed, go with its square
      density *= std::sqrt(height <= size ? std::min(double(size) / std::max(height, 1), 4.0)
                                          : std::clamp(std::min(placed, double(size) / height), 0.25, 0.9));
    if (fits > 0 && fails > 0 && fails / fits < 1.005) break;
  }
  for (std::size_t i = 0; i < charts.size(); ++i) {
    const Spot& s = best_spots[i];
    const Footprint& f = best_prints[i][std::size_t(s.turn)];
    const Placement p = s.turn < 2 ? place[i] : place[i].quarterTurn();
    for (UV& q : charts[i].uv) {
      const UV r = p.apply(q);
      UV at{grow + fits * r[0], grow + fits * r[1]};  // in the footprint
      if (s.turn % 2 == 1) at = {f.width - at[0], f.height - at[1]};
      // Rows of the map run down; the chart's up is the image's up.
      q = {(s.x + at[0]) / size, 1.0 - (s.y + at[1]) / size};
    }
  }
  return fits;
}

}  // namespace rockbake
