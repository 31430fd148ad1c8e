#include "texture/pack_charts.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "texture/texture_params.h"

namespace rockbake {
namespace {

using UV = std::array<double, 2>;

constexpr int kRounds = 8;  // rounds of packing that search the density
// A texel belongs to a chart's footprint where its centre lies within this many texels of one
// of the chart's triangles: what the atlas's rasteriser (rasterize_uv.h) may claim once the uv
// are rounded to float and snapped to 1/256 texel, with room to spare.
constexpr double kCoverMargin = 1.0 / 64.0;

double cross(const UV& o, const UV& a, const UV& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
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

// Rows [from, to) of one column.
struct Run {
  int from = 0, to = 0;  // rows [from, to)
};

// Run lengths in classes, for the occupancy's lowest gap per class (Occupancy::lowest): every
// length up to kExactLengths rows, then powers of two up to 2^15 rows. classLength(k) is the
// shortest length of class k.
constexpr int kExactLengths = 32, kLengthClasses = kExactLengths + 10;
constexpr int classLength(int k) {
  return k < kExactLengths ? k + 1 : kExactLengths << (k - kExactLengths + 1);
}
int lengthClass(int length) {
  return length <= kExactLengths
             ? length - 1
             : std::min(kLengthClasses - 1, kExactLengths - 1 + int(std::bit_width(unsigned(length))) - 6);
}

// A chart's footprint at one density: per column of texels, the runs of rows whose texel
// centres its triangles cover (ascending, apart), grown by `grow` texels each way (a chessboard
// dilation), with the chart itself `grow` texels in from the footprint's lower corner.
struct Footprint {
  int width = 0, height = 0;
  std::vector<std::vector<Run>> columns;
  // The same runs in one array, column by column, and per column that has any, its longest run
  // as the lower bound reads it: the drop's loops walk contiguous memory.
  struct Probe {
    int column, length_class, from;
  };
  struct Cell {
    int column, from, to;
  };
  std::vector<Cell> cells;
  std::vector<Probe> probes;
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

// Fills a footprint's flat arrays from its columns.
void seal(Footprint& f) {
  f.cells.clear(), f.probes.clear();
  for (int i = 0; i < f.width; ++i) {
    const auto& runs = f.columns[std::size_t(i)];
    for (const Run& r : runs) f.cells.push_back({i, r.from, r.to});
    if (runs.empty()) continue;
    const Run longest = *std::max_element(runs.begin(), runs.end(),
                                          [](const Run& a, const Run& b) { return a.to - a.from < b.to - b.from; });
    f.probes.push_back({i, lengthClass(longest.to - longest.from), longest.from});
  }
}

Footprint footprint(const PackChart& chart, const Placement& place, double density, int grow) {
  const int width = int(std::ceil(density * place.width)) + 1, height = int(std::ceil(density * place.height)) + 1;
  std::vector<std::vector<Run>> touched(static_cast<std::size_t>(width));
  std::vector<UV> p(chart.uv.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const UV q = place.apply(chart.uv[i]);
    p[i] = {density * q[0], density * q[1]};
  }
  // A texel is the chart's where its centre lies in the triangle grown by kCoverMargin (each
  // edge pushed out along its normal): the texels the atlas's rasteriser gives the chart, and
  // no more, so gutters are `padding` texels of the map, not of conservative outlines.
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
      off[k] = kCoverMargin * std::hypot(nx[k], ny[k]) - (nx[k] * s[0] + ny[k] * s[1]);
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
  seal(f);
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
  seal(r);
  return r;
}

struct Spot {
  int x = 0, y = 0, turn = 0;
};

// The texels packed so far, kept twice: per column a bit per row (1: taken by a grown
// footprint), to test a run's rows in a word or two, and per column its free gaps (rows
// [from, to), ascending), to lift a run past every gap too short for it in one step. Per column
// and length class, the lowest gap of at least that class's length: no run of that length sits
// lower. Rows 0 … 4 · size − 1: packings taller than the map are measured too, to rescale the
// density.
class Occupancy {
 public:
  Occupancy(int columns, int rows)
      : rows_(rows),
        words_(std::size_t(rows + 63) / 64),
        bits_(std::size_t(columns) * words_, 0),
        gaps_(std::size_t(columns), std::vector<Run>{{0, rows}}),
        lowest_(std::size_t(columns) * kLengthClasses, 0) {}

  int rows() const { return rows_; }

  // Column x's lowest gap of a length class (lengthClass).
  int lowest(int x, int length_class) const {
    return lowest_[std::size_t(x) * kLengthClasses + std::size_t(length_class)];
  }

  // Whether any of rows [from, to) of column x is taken (0 ≤ from < to ≤ rows()).
  bool blocked(int x, int from, int to) const {
    const std::uint64_t* col = &bits_[std::size_t(x) * words_];
    const int first = from >> 6, last = (to - 1) >> 6;
    const std::uint64_t low = ~std::uint64_t(0) << (from & 63), high = ~std::uint64_t(0) >> (63 - ((to - 1) & 63));
    if (first == last) return (col[first] & low & high) != 0;
    if (col[first] & low) return true;
    for (int w = first + 1; w < last; ++w)
      if (col[w]) return true;
    return (col[last] & high) != 0;
  }

  // The lowest row t ≥ from where rows [t, t + length) of column x are free, or −1 when there
  // is none at or below `limit`. `gaps_passed` counts the gaps looked at above `from`'s.
  int fit(int x, int from, int length, int limit, std::uint64_t& gaps_passed) const {
    const std::vector<Run>& gaps = gaps_[std::size_t(x)];
    auto g = std::upper_bound(gaps.begin(), gaps.end(), from, [](int row, const Run& r) { return row < r.from; });
    if (g != gaps.begin() && std::prev(g)->to - from >= length) return from;  // the gap holding `from`
    for (; g != gaps.end() && g->from <= limit; ++g) {
      ++gaps_passed;
      if (g->to - g->from >= length) return g->from;
    }
    return -1;
  }

  // Takes rows [from, to) of column x, which must be free.
  void take(int x, int from, int to) {
    std::uint64_t* col = &bits_[std::size_t(x) * words_];
    for (int r = from; r < to;) {
      const int end = std::min(to, (r | 63) + 1), n = end - r;
      col[r >> 6] |= (n == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << n) - 1) << (r & 63);
      r = end;
    }
    std::vector<Run>& gaps = gaps_[std::size_t(x)];
    const auto g =
        std::prev(std::upper_bound(gaps.begin(), gaps.end(), from, [](int row, const Run& r) { return row < r.from; }));
    const Run was = *g;
    const std::size_t at = std::size_t(g - gaps.begin());
    if (was.from < from && to < was.to) {
      g->to = from;
      gaps.insert(g + 1, Run{to, was.to});
    } else if (was.from < from) {
      g->to = from;
    } else if (to < was.to) {
      g->from = to;
    } else {
      gaps.erase(g);
    }
    // Only the classes whose lowest gap was this one change: theirs is this one's remainder or
    // a later gap. The last gap stands for any length (what does not fit there fits nowhere).
    for (int k = 0; k < kLengthClasses; ++k) {
      int& lowest = lowest_[std::size_t(x) * kLengthClasses + std::size_t(k)];
      if (lowest != was.from) continue;
      std::size_t i = at;
      while (i < gaps.size() && gaps[i].to - gaps[i].from < classLength(k) && gaps[i].to < rows_) ++i;
      lowest = i < gaps.size() ? gaps[i].from : rows_;
    }
  }

 private:
  int rows_;
  std::size_t words_;
  std::vector<std::uint64_t> bits_;
  std::vector<std::vector<Run>> gaps_;
  std::vector<int> lowest_;  // column-major: a drop reads neighbouring columns
};

// No row below this one lets a footprint with its first column at x meet no taken texel: each
// column's longest run sits in a gap at least as long. Stops early once above `above`.
int lowerBound(const Footprint& f, const Occupancy& taken, int x, int above) {
  int y = 0;
  for (const Footprint::Probe& p : f.probes) {
    y = std::max(y, taken.lowest(x + p.column, p.length_class) - p.from);
    if (y > above) break;
  }
  return y;
}

// The lowest row y ≥ `from` (a lower bound) at which a footprint with its first column at x
// meets no taken texel (in a hole beneath earlier charts as well as on top of them), or
// nothing when that is higher than `above` (the best found so far) or than the rows held. The
// runs are tested in turn, round and round; one that meets a taken texel lifts the footprint to
// the next gap long enough for it in its column, until every run in a row fits.
bool lowestFree(const Footprint& f, const Occupancy& taken, int x, int from, int above, int& y, PackWork& work) {
  y = from;
  if (y > above) return false;
  const std::size_t n = f.cells.size();
  for (std::size_t r = 0, clean = 0; clean < n; r = r + 1 == n ? 0 : r + 1) {
    const Footprint::Cell& c = f.cells[r];
    if (!taken.blocked(x + c.column, y + c.from, y + c.to)) {
      ++clean;
      continue;
    }
    const int limit = above >= taken.rows() ? taken.rows() : above + c.from;
    const int t = taken.fit(x + c.column, y + c.from, c.to - c.from, limit, work.gaps_passed);
    ++work.lifts;
    if (t < 0) return false;
    y = t - c.from;
    if (y > above) return false;
    clean = 1;
  }
  return true;
}

// Every chart placed, biggest first, where it rests lowest in what is packed so far (holes
// left beneath earlier charts included; ties: the first found, turn by turn, left to right):
// every kStride-th column first, then each column near the best of those. Returns the
// packing's height, or more than `size` when a chart is wider than the map or the packing
// outgrows the map (it stops there: `placed` gives the share of the footprints' texels placed
// by then, 1 when all fit).
int drop(const std::vector<std::array<Footprint, 4>>& prints, const std::vector<std::size_t>& order, int size,
         std::vector<Spot>& spots, double& placed, PackWork& work) {
  constexpr int kStride = 8;
  Occupancy taken(size, 4 * size);
  int height = 0;
  double placed_texels = 0, texels = 0;
  for (const auto& p : prints)
    for (const Footprint::Cell& c : p[0].cells) texels += c.to - c.from;
  spots.assign(prints.size(), Spot{});
  for (std::size_t c : order) {
    int best_y = std::numeric_limits<int>::max();
    Spot best{-1, 0, 0};
    const auto consider = [&](int turn, int x) {
      const Footprint& f = prints[c][std::size_t(turn)];
      ++work.positions;
      const int bound = lowerBound(f, taken, x, best_y - 1);
      int y = 0;
      if (bound < best_y && lowestFree(f, taken, x, bound, best_y - 1, y, work)) best_y = y, best = {x, y, turn};
    };
    for (int turn = 0; turn < 4; ++turn) {
      const int last = size - prints[c][std::size_t(turn)].width;
      for (int x = 0; x <= last; x += kStride) consider(turn, x);
      if (last >= 0 && last % kStride != 0) consider(turn, last);
    }
    if (best.x < 0) {
      placed = 0;  // wider than the map, or taller than the rows held: shrink as far as a round may
      return std::numeric_limits<int>::max();
    }
    const Spot coarse = best;
    const int last = size - prints[c][std::size_t(coarse.turn)].width;
    for (int x = std::max(0, coarse.x - kStride + 1); x <= std::min(last, coarse.x + kStride - 1); ++x)
      if (x != coarse.x) consider(coarse.turn, x);
    const Footprint& f = prints[c][std::size_t(best.turn)];
    for (const Footprint::Cell& cell : f.cells) {
      taken.take(best.x + cell.column, best.y + cell.from, best.y + cell.to);
      height = std::max(height, best.y + cell.to);
      placed_texels += cell.to - cell.from;
    }
    spots[c] = best;
    ++work.charts;
    if (height > size) break;
  }
  placed = texels > 0 ? placed_texels / texels : 1.0;
  return height;
}

}  // namespace

std::vector<std::array<double, 2>> convexHull(std::vector<std::array<double, 2>> p) {
  using UV = std::array<double, 2>;
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

double convexHullArea(const std::vector<UV>& points) {
  const std::vector<UV> hull = convexHull(points);
  double twice = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const UV &a = hull[i], &b = hull[(i + 1) % hull.size()];
    twice += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * std::abs(twice);
}

double packCharts(std::vector<PackChart>& charts, int size, int padding, PackWork* counts) {
  PackWork work;
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
  int fits_height = 0;
  std::vector<Spot> spots, best_spots;
  std::vector<std::array<Footprint, 4>> prints(charts.size()), best_prints;
  for (int round = 0; round < kRounds || fits == 0; ++round) {
    if (round > 4 * kRounds)
      throw ChartsDoNotFit("cannot pack " + std::to_string(charts.size()) + " UV charts into a " +
                           std::to_string(size) + "² map with " + std::to_string(padding) +
                           "-texel gutters (raise texture.size or lower texture.padding)");
    prints.resize(charts.size());
    tbb::parallel_for(std::size_t(0), charts.size(), [&](std::size_t i) {
      prints[i][0] = footprint(charts[i], place[i], density, grow);
      prints[i][1] = halfTurn(prints[i][0]);
      prints[i][2] = footprint(charts[i], place[i].quarterTurn(), density, grow);
      prints[i][3] = halfTurn(prints[i][2]);
    });
    double placed = 1;
    const int height = drop(prints, order, size, spots, placed, work);
    if (height <= size) {
      fits = density;
      fits_height = height;
      best_spots = spots;
      std::swap(best_prints, prints);    // the next round makes every footprint afresh
      if (height >= 0.98 * size) break;  // within 1 % of the density that fills the map
    } else {
      fails = density;
    }
    if (fits > 0 && fails > 0)  // where the last fit's height says 99 % of the map is, if that is nearer than halfway
      density =
          std::clamp(fits * std::sqrt(0.99 * size / std::max(fits_height, 1)), fits * 1.001, std::sqrt(fits * fails));
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
  if (counts) *counts = work;
  return fits;
}

}  // namespace rockbake
