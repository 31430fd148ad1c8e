// The look made by surface processes (docs/model.md §14). Water: Dorsey, Pedersen and Hanrahan
// 1996, "Flow and changes in appearance" (SIGGRAPH), and Chen, Xia, Wong, Tong, Bao, Guo and
// Shum 2005, "Visual simulation of weathering by γ-ton tracing" (SIGGRAPH): rain falls on what
// faces the open sky, runs down the fall line and drips from overhangs, and what it carries is
// left where it runs over steep rock. Routing follows the fall line over the mesh's facets
// (Tarboton 1997, D∞) with a little multiple-flow-direction spread (Quinn, Beven, Chevallier and
// Planchon 1991; Freeman 1991) for a streak's width; hollows fill and spill (a priority flood,
// Barnes, Lehman and Mulla 2014); what the water carries is laid down along its path, so
// streaks run long down the fall line. The flood orders the vertices; serial passes in that order
// accumulate the water and spread its deposit; everything else is per vertex, in parallel: the
// same look at any thread count.
#include "mesh/surface_look.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "core/vec3.h"
#include "geometry/triangle_geometry.h"
#include "geometry/vertex_faces.h"

namespace rockbake {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// Where the normal points further down than this (n_z), water no longer follows the surface: it
// is shed and drips straight down. A film clings to a surface that only leans a little past the
// vertical (a drop falls once gravity's pull off the surface beats its adhesion, as in Dorsey et
// al.); past about 37° it lets go.
constexpr double kShedNz = -0.6;
// The spread's exponent on each lower neighbour's descent (drop over edge length): at 8 a
// neighbour 45° off the fall line gets 1/16 of the share of one on it.
constexpr double kRoutingExponent = 8.0;
// Flow is measured as specific catchment (the rain area upstream per unit width of the stream),
// in voxels: a stream that drained a strip kStainLength voxels long stains 1 − 1/e of the full.
constexpr double kStainLength = 8.0;
// Stain is spread along the water's path: kDepositPasses times weighted exp(−distance /
// kDepositLength voxels), about a Gaussian of 6 voxels' deviation (streaks are long).
constexpr double kDepositLength = 3.0;
constexpr int kDepositPasses = 2;
// Where less water runs than this (its own 1 − exp(−catchment / kStainLength), a catchment of
// about 0.16 voxel), less is laid down; where none runs, nothing.
constexpr double kRunning = 0.02;
// G: a streak's stain is kStainAmount on old rock, kStainFresh of that on a face exposed at the
// last cycle; varnish grows as kVarnishAmount · (time in the open)^kVarnishExponent, off the
// streaks kVarnishOffStreak of what it is on them. Time against colluvium counts kBuriedShare.
constexpr double kStainAmount = 0.8;
constexpr double kStainFresh = 0.2;
constexpr double kVarnishAmount = 0.3;
constexpr double kVarnishExponent = 1.0;
constexpr double kVarnishOffStreak = 0.35;
constexpr double kBuriedShare = 0.25;
// A stream washes dust off once it has drained about kWashLength voxels.
constexpr double kWashLength = 12.0;
// The damp band at the foot, voxels: its e-folding height, and the height where it has faded
// to 0 (exp(−4 / 1.5) = 7 % of it is faded out over the band).
constexpr double kBand = 1.5;
constexpr int kBandReach = 4;
// How far from the rock (voxels) the colluvium's damp contact reaches; it fades to 0 there.
constexpr int kContactReach = 3;
// Drips land on the highest rock within this many voxels horizontally below the lip; at most
// kDripScan candidates are looked at in each bucket.
constexpr double kDripRadius = 1.0;
constexpr std::size_t kDripScan = 512;
// How far along its normal (voxels) a vertex's grid samples are taken: off the rock, into the air.
constexpr double kSampleOffset = 0.6;

// The final grid as the look reads it: material with the ground below k = 0; each column's
// highest solid voxel (rock or colluvium), what shelters the air below it from the sky; and each
// column's rock height range, which lets the colluvium's search for the rock pass most columns.
class GridView {
 public:
  explicit GridView(const VoxelRock& rock)
      : rock_(rock),
        g_(rock.layout),
        top_(std::size_t(g_.nx) * g_.ny, -1),
        rock_lo_(top_.size(), std::numeric_limits<int>::max()),
        rock_hi_(top_.size(), -1) {
    if (rock.material.size() != g_.cellCount())
      throw std::invalid_argument("makeSurfaceLook: the grid's materials do not match its layout");
    tbb::parallel_for(0, g_.ny, [&](int y) {
      for (int z = 0; z < g_.nz; ++z)
        for (int x = 0; x < g_.nx; ++x) {
          const Material m = rock_.material[g_.index(x, y, z)];
          const std::size_t column = std::size_t(x) + std::size_t(g_.nx) * y;
          if (m != Material::Air) top_[column] = z;
          if (m == Material::Rock) rock_lo_[column] = std::min(rock_lo_[column], z), rock_hi_[column] = z;
        }
    });
  }

  double h() const { return g_.h; }

  std::array<int, 3> cell(const Vec3d& p) const {
    return {int(std::floor((p[0] - g_.origin[0]) / g_.h)), int(std::floor((p[1] - g_.origin[1]) / g_.h)),
            int(std::floor((p[2] - g_.origin[2]) / g_.h))};
  }

  Material material(int x, int y, int z) const {
    if (!g_.contains(x, y, z)) return (z < 0 && g_.ground) ? Material::Rock : Material::Air;
    return rock_.material[g_.index(x, y, z)];
  }

  // Whether solid lies above the cell (or the ground around it, for a cell below k = 0).
  bool sheltered(const std::array<int, 3>& c) const {
    if (c[0] < 0 || c[1] < 0 || c[0] >= g_.nx || c[1] >= g_.ny || c[2] >= g_.nz) return false;
    if (c[2] < 0 && g_.ground) return true;
    return top_[std::size_t(c[0]) + std::size_t(g_.nx) * c[1]] > c[2];
  }

  // The share of the open sky above a vertex: five columns around the point kSampleOffset off it.
  double skyVisibility(const Vec3d& p, const Vec3d& n) const {
    const Vec3d s = add(p, scale(n, kSampleOffset * g_.h));
    constexpr double kJitter = 0.35;
    constexpr double kOffsets[5][2] = {{0, 0}, {kJitter, 0}, {-kJitter, 0}, {0, kJitter}, {0, -kJitter}};
    int open = 0;
    for (const auto& o : kOffsets) open += !sheltered(cell({s[0] + o[0] * g_.h, s[1] + o[1] * g_.h, s[2]}));
    return open / 5.0;
  }

  // The height of p above the first colluvium or ground met going down through the air from
  // kSampleOffset off it, within kBandReach voxels; infinity where rock (a ledge) comes first or
  // nothing is that near.
  double heightAboveWet(const Vec3d& p, const Vec3d& n) const {
    const std::array<int, 3> c = cell(add(p, scale(n, kSampleOffset * g_.h)));
    for (int z = c[2]; z >= c[2] - kBandReach - 2; --z) {  // the sample is at most 0.6 voxel above p
      const Material m = material(c[0], c[1], z);
      if (m == Material::Air) continue;
      if (m == Material::Rock && !(z < 0 && g_.ground)) break;
      const double surface = z < 0 ? 0.0 : g_.origin[2] + (z + 1) * g_.h;  // the ground is z = 0
      const double height = std::max(0.0, p[2] - surface);
      return height <= kBandReach * g_.h ? height : std::numeric_limits<double>::infinity();
    }
    return std::numeric_limits<double>::infinity();
  }

  // The distance from p to the nearest rock voxel within kContactReach voxels, or infinity.
  // A column no nearer than the best so far, or without rock in reach (by its rock's height
  // range), is passed over; in a column, the first rock up or down from p's layer is its nearest.
  double distanceToRock(const Vec3d& p) const {
    constexpr int kSide = 2 * kContactReach + 1;
    const std::array<int, 3> c = cell(p);
    // The distance along axis a from p to cell i's extent.
    const auto gap = [&](int a, int i) {
      const double lo = g_.origin[a] + i * g_.h, hi = lo + g_.h;
      return p[a] < lo ? lo - p[a] : (p[a] > hi ? p[a] - hi : 0.0);
    };
    std::array<double, kSide> gx2, gy2, gz;
    for (int k = 0; k < kSide; ++k) {
      const double x = gap(0, c[0] - kContactReach + k), y = gap(1, c[1] - kContactReach + k);
      gx2[k] = x * x, gy2[k] = y * y, gz[k] = gap(2, c[2] - kContactReach + k);
    }
    double best = std::numeric_limits<double>::infinity();  // squared
    for (int j = 0; j < kSide; ++j) {
      const int y = c[1] - kContactReach + j;
      if (y < 0 || y >= g_.ny) continue;
      for (int i = 0; i < kSide; ++i) {
        const int x = c[0] - kContactReach + i;
        const double flat = gx2[i] + gy2[j];
        if (x < 0 || x >= g_.nx || flat >= best) continue;
        const std::size_t column = std::size_t(x) + std::size_t(g_.nx) * y;
        if (rock_lo_[column] > c[2] + kContactReach || rock_hi_[column] < c[2] - kContactReach) continue;
        for (int step = 0; step <= kContactReach; ++step) {
          const double below = gz[kContactReach - step], above = gz[kContactReach + step];
          if (flat + std::min(below, above) * std::min(below, above) >= best) break;
          bool found = false;
          for (const int k : {kContactReach - step, kContactReach + step}) {
            const int z = c[2] - kContactReach + k;
            if (z < rock_lo_[column] || z > rock_hi_[column] || rock_.material[g_.index(x, y, z)] != Material::Rock)
              continue;
            best = std::min(best, flat + gz[k] * gz[k]);
            found = true;
          }
          if (found) break;
        }
      }
    }
    return std::sqrt(best);
  }

  bool ground() const { return g_.ground; }

 private:
  const VoxelRock& rock_;
  const GridLayout& g_;
  std::vector<int> top_;                // per column (x + nx y): the highest solid k, −1 none
  std::vector<int> rock_lo_, rock_hi_;  // per column: the lowest and highest rock k (hi −1: none)
};

// A float's bits as an unsigned key in the same order.
std::uint32_t orderedBits(float f) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(f);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
float fromOrderedBits(std::uint32_t k) {
  return std::bit_cast<float>((k & 0x80000000u) ? (k & 0x7fffffffu) : ~k);
}

// The mesh's triangles, its quads split in two (the look reads triangles only).
std::vector<std::array<std::uint32_t, 3>> allTriangles(const SurfaceMesh& m) {
  std::vector<std::array<std::uint32_t, 3>> t = m.triangles;
  for (const auto& q : m.quads) t.push_back({q[0], q[1], q[2]}), t.push_back({q[0], q[2], q[3]});
  return t;
}

// Each vertex's share of its triangles' areas (a third of each).
std::vector<double> vertexAreas(const SurfaceMesh& m, const std::vector<std::array<std::uint32_t, 3>>& tris,
                                const VertexFaces& faces) {
  std::vector<double> tri_area(tris.size());
  tbb::parallel_for(std::size_t(0), tris.size(), [&](std::size_t f) {
    const auto& t = tris[f];
    tri_area[f] = triangleArea(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  });
  std::vector<double> area(m.positions.size());
  tbb::parallel_for(std::size_t(0), area.size(), [&](std::size_t v) {
    double a = 0;
    for (std::uint32_t f : faces[std::uint32_t(v)]) a += tri_area[f];
    area[v] = a / 3.0;
  });
  return area;
}

// The order water leaves the surface in, by a priority flood from its outlets (Barnes, Lehman
// and Mulla 2014, "Priority-flood: an optimal depression-filling and watershed-labeling
// algorithm"): the surface is flooded upwards from where water leaves it (overhangs that shed
// it, the ground, colluvium it soaks into; for a part with none of those, its lowest vertex),
// each vertex reached at the higher of its own height and the level it was reached at. Vertices
// come out lowest level first; water runs the other way, so a vertex's rank (0 the last out) is
// below that of every vertex it can give water to. A vertex raised above its own height lies in
// a hollow (a weathering pit, a tafone) that fills to its spill point: within the hollow water
// still runs down its walls, highest first (each level's raised vertices are put in height
// order), and what reaches its bottom spills over at `spill`. On a dead flat water goes the way
// the flood came (`parent`). Serial, keyed by (level, index): the same at any thread count.
struct Drainage {
  std::vector<std::uint32_t> rank;
  std::vector<std::uint32_t> parent;  // the vertex that flooded it; kNone for an outlet
  std::vector<std::uint32_t> spill;   // for a raised vertex, where its hollow spills; else kNone
};

Drainage drainage(const SurfaceMesh& m, const VertexFaces& faces, const std::vector<std::array<std::uint32_t, 3>>& tris,
                  double h, bool ground) {
  const std::size_t n = m.positions.size();
  Drainage d;
  d.rank.assign(n, 0);
  d.parent.assign(n, kNone);
  d.spill.assign(n, kNone);
  const auto key = [](float level, std::uint32_t v) { return (std::uint64_t(orderedBits(level)) << 32) | v; };
  std::vector<std::uint64_t> heap;
  std::vector<char> pushed(n, 0);
  const float ground_z = float(1e-3 * h);
  for (std::uint32_t v = 0; v < n; ++v)
    if (m.normals[v][2] < kShedNz || (ground && m.positions[v][2] <= ground_z) ||
        (!m.colluvium.empty() && m.colluvium[v] >= 0.5f))
      heap.push_back(key(m.positions[v][2], v)), pushed[v] = 1;
  const auto later = std::greater<std::uint64_t>();  // a min-heap
  std::make_heap(heap.begin(), heap.end(), later);
  std::vector<std::uint64_t> lowest;  // every vertex by height, made only if a part has no outlet
  std::size_t cursor = 0;
  std::vector<std::uint64_t> popped(n);  // (level, vertex), in the order they come out
  for (std::size_t out = 0; out < n; ++out) {
    if (heap.empty()) {
      if (lowest.empty()) {
        lowest.resize(n);
        tbb::parallel_for(std::size_t(0), n,
                          [&](std::size_t v) { lowest[v] = key(m.positions[v][2], std::uint32_t(v)); });
        tbb::parallel_sort(lowest.begin(), lowest.end());  // unique keys
      }
      while (pushed[lowest[cursor] & 0xffffffffu]) ++cursor;
      heap.push_back(lowest[cursor]);
      pushed[lowest[cursor] & 0xffffffffu] = 1;
    }
    std::pop_heap(heap.begin(), heap.end(), later);
    const std::uint64_t top = heap.back();
    heap.pop_back();
    popped[out] = top;
    const std::uint32_t u = std::uint32_t(top & 0xffffffffu);
    const float level = fromOrderedBits(std::uint32_t(top >> 32));
    for (std::uint32_t f : faces[u])
      for (std::uint32_t w : tris[f]) {
        if (pushed[w]) continue;
        pushed[w] = 1;
        d.parent[w] = u;
        const float z = m.positions[w][2];
        if (level > z) d.spill[w] = d.spill[u] != kNone ? d.spill[u] : u;
        heap.push_back(key(std::max(z, level), w));
        std::push_heap(heap.begin(), heap.end(), later);
      }
  }
  // Each level comes out in one run; where a run holds raised vertices, they follow the others,
  // lowest first (so that water, taking them in reverse, runs down a hollow's walls).
  for (std::size_t a = 0; a < n;) {
    std::size_t b = a + 1;
    while (b < n && (popped[b] >> 32) == (popped[a] >> 32)) ++b;
    const auto raised = [&](std::uint64_t k) { return d.spill[k & 0xffffffffu] != kNone; };
    if (std::any_of(popped.begin() + std::ptrdiff_t(a), popped.begin() + std::ptrdiff_t(b), raised)) {
      const auto first = std::stable_partition(popped.begin() + std::ptrdiff_t(a), popped.begin() + std::ptrdiff_t(b),
                                               [&](std::uint64_t k) { return !raised(k); });
      std::sort(first, popped.begin() + std::ptrdiff_t(b), [&](std::uint64_t x, std::uint64_t y) {
        const std::uint32_t u = std::uint32_t(x & 0xffffffffu), v = std::uint32_t(y & 0xffffffffu);
        const float zu = m.positions[u][2], zv = m.positions[v][2];
        return zu < zv || (zu == zv && u < v);
      });
    }
    a = b;
  }
  for (std::size_t i = 0; i < n; ++i) d.rank[popped[i] & 0xffffffffu] = std::uint32_t(n - 1 - i);
  return d;
}

// Where the water shed by each overhanging vertex (n_z < kShedNz) lands: the highest vertex
// that is not overhanging, strictly below it and within kDripRadius voxels horizontally, found
// in a bucket grid of h-wide columns sorted by height; kNone where nothing is (it falls off the
// rock, onto the colluvium or the ground).
std::vector<std::uint32_t> dripTargets(const SurfaceMesh& m, double h) {
  const std::size_t n = m.positions.size();
  std::vector<std::uint32_t> target(n, kNone);
  float lo[2] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
  float hi[2] = {std::numeric_limits<float>::lowest(), std::numeric_limits<float>::lowest()};
  for (const auto& p : m.positions)
    for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  if (n == 0) return target;
  const int w = int((hi[0] - lo[0]) / h) + 1, d = int((hi[1] - lo[1]) / h) + 1;
  const auto bucketOf = [&](double x, double y, int& bx, int& by) {
    bx = std::clamp(int((x - lo[0]) / h), 0, w - 1);
    by = std::clamp(int((y - lo[1]) / h), 0, d - 1);
  };
  struct Entry {
    float x, y, z;
    std::uint32_t v;
  };
  std::vector<std::size_t> start(std::size_t(w) * d + 1, 0);
  std::vector<std::uint32_t> bucket(n, kNone);
  for (std::uint32_t v = 0; v < n; ++v) {
    if (m.normals[v][2] < kShedNz) continue;
    int bx, by;
    bucketOf(m.positions[v][0], m.positions[v][1], bx, by);
    bucket[v] = std::uint32_t(bx + w * by);
    ++start[bucket[v] + 1];
  }
  for (std::size_t b = 0; b + 1 < start.size(); ++b) start[b + 1] += start[b];
  std::vector<Entry> entries(start.back());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t v = 0; v < n; ++v)
      if (bucket[v] != kNone) {
        const auto& p = m.positions[v];
        entries[fill[bucket[v]]++] = {p[0], p[1], p[2], v};
      }
  }
  // Highest first, ties by index: a total order.
  const auto higher = [](const Entry& a, const Entry& b) { return a.z > b.z || (a.z == b.z && a.v < b.v); };
  tbb::parallel_for(std::size_t(0), start.size() - 1, [&](std::size_t b) {
    std::sort(entries.begin() + std::ptrdiff_t(start[b]), entries.begin() + std::ptrdiff_t(start[b + 1]), higher);
  });

  const double r2 = (kDripRadius * h) * (kDripRadius * h);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    if (m.normals[v][2] >= kShedNz) return;
    const auto& p = m.positions[v];
    int bx, by;
    bucketOf(p[0], p[1], bx, by);
    Entry best{0, 0, std::numeric_limits<float>::lowest(), kNone};
    for (int y = std::max(by - 1, 0); y <= std::min(by + 1, d - 1); ++y)
      for (int x = std::max(bx - 1, 0); x <= std::min(bx + 1, w - 1); ++x) {
        const std::size_t b = std::size_t(x) + std::size_t(w) * y;
        const auto first = std::partition_point(entries.begin() + std::ptrdiff_t(start[b]),
                                                entries.begin() + std::ptrdiff_t(start[b + 1]),
                                                [&](const Entry& e) { return e.z >= p[2]; });
        const auto last = entries.begin() + std::ptrdiff_t(start[b + 1]);
        std::size_t scanned = 0;
        for (auto e = first; e != last && scanned < kDripScan; ++e, ++scanned) {
          if (best.v != kNone && !higher(*e, best)) break;
          const double dx = double(e->x) - p[0], dy = double(e->y) - p[1];
          if (dx * dx + dy * dy <= r2) {
            best = *e;
            break;
          }
        }
      }
    target[v] = best.v;
  });
  return target;
}

// Where each vertex's water goes: receivers (ranks, each above its giver's) with their shares.
// An overhanging vertex sheds all of it to its drip target; the bottom of a filled hollow passes
// it to the hollow's spill point, a vertex on a dead flat the way the flood came (Drainage).
// Elsewhere water takes the fall line: Tarboton's (1997) D∞ on the vertex's facets (the steepest
// facet's downhill direction, split between the two edges around it so that the mean step is
// along it; where it leaves its wedge, the steeper edge), blended with a little multiple-flow-
// direction spread (kSpread of the water shared over the lower neighbours by
// descent^kRoutingExponent) for a streak's width. At most kReceivers receivers, the largest
// shares (the rest, a few thousandths, go to them).
constexpr double kSpread = 0.2;
constexpr int kReceivers = 4;

struct Receivers {
  std::array<std::uint32_t, kReceivers> to;  // ranks; kNone past the last
  std::array<float, kReceivers> share;
};

// A lower neighbour's weight in the spread from the squared sine of its descent (relative to the
// steepest): sine^kRoutingExponent.
double spreadWeight(double sine2) {
  static_assert(kRoutingExponent == 8.0);
  sine2 *= sine2;
  return sine2 * sine2;
}

// By rank.
std::vector<Receivers> route(const SurfaceMesh& m, const VertexFaces& faces,
                             const std::vector<std::array<std::uint32_t, 3>>& tris, const Drainage& drain,
                             const std::vector<std::uint32_t>& drip) {
  const std::size_t n = m.positions.size();
  const std::vector<std::uint32_t>& rank = drain.rank;
  // The receivers of vertex v, of rank r (ranks, increasing), and their shares.
  const auto lower = [&](std::uint32_t v, std::uint32_t r, std::vector<std::uint32_t>& nb, std::vector<double>& w) {
    nb.clear();
    w.clear();
    // All of it to one vertex, where it comes later.
    const auto toOne = [&](std::uint32_t u) {
      if (u != kNone && rank[u] > r) nb.push_back(rank[u]), w.push_back(1.0);
    };
    if (m.normals[v][2] < kShedNz) return toOne(drip[v]);  // shed: it drips (or falls off the rock)
    const Vec3d p = toVec3d(m.positions[v]);
    // The squared sine of an edge's descent from v (0 where it does not descend): slopes are
    // compared squared, without a square root.
    const auto descent2 = [](const Vec3d& e) {
      const double l2 = dot(e, e);
      return e[2] < 0 && l2 > 0 ? e[2] * e[2] / l2 : 0.0;
    };
    // D∞: the steepest facet direction, to (ba, bb) with shares (sa, sb); and the lower neighbours.
    double best = 0, sa = 0, sb = 0;
    std::uint32_t ba = kNone, bb = kNone;
    for (std::uint32_t f : faces[v]) {
      const auto& t = tris[f];
      const int c = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
      const std::uint32_t a = t[(c + 1) % 3], b = t[(c + 2) % 3];
      if (a == v || b == v) continue;
      const Vec3d e1 = sub(toVec3d(m.positions[a]), p), e2 = sub(toVec3d(m.positions[b]), p);
      const double d1 = descent2(e1), d2 = descent2(e2);
      for (const auto& [u, d] : {std::pair{a, d1}, std::pair{b, d2}})
        if (rank[u] > r && std::find(nb.begin(), nb.end(), u) == nb.end()) nb.push_back(u), w.push_back(d);
      const Vec3d nt = cross(e1, e2);
      const double h2 = nt[0] * nt[0] + nt[1] * nt[1], l2 = h2 + nt[2] * nt[2];
      if (!(h2 > 0)) continue;  // flat (or degenerate)
      // The facet's downhill direction (times |nt|²): −z less its part along the facet's normal.
      const Vec3d d = {nt[2] * nt[0], nt[2] * nt[1], -h2};
      const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
      const double det = g11 * g22 - g12 * g12;
      const double r1 = dot(d, e1), r2 = dot(d, e2);
      const double alpha = det > 0 ? (r1 * g22 - r2 * g12) / det : -1.0;
      const double beta = det > 0 ? (r2 * g11 - r1 * g12) / det : -1.0;
      if (alpha >= 0 && beta >= 0 && alpha + beta > 0) {
        const double slope2 = h2 / l2;
        if (slope2 > best) best = slope2, ba = a, bb = b, sa = alpha / (alpha + beta), sb = beta / (alpha + beta);
      } else if (std::max(d1, d2) > best) {  // it leaves the wedge: along its steeper edge
        best = std::max(d1, d2), ba = d1 >= d2 ? a : b, bb = kNone, sa = 1.0, sb = 0.0;
      }
    }
    if (ba != kNone && rank[ba] <= r) sa = 0;
    if (bb != kNone && rank[bb] <= r) sb = 0;
    // The spread: every lower neighbour by its descent^kRoutingExponent.
    double top = 0;
    for (double x : w) top = std::max(top, x);
    if (top <= 0 || sa + sb <= 0) {  // nothing lower: a hollow's bottom spills, a flat drains
      nb.clear();
      w.clear();
      return toOne(drain.spill[v] != kNone ? drain.spill[v] : drain.parent[v]);
    }
    double sum = 0;
    for (double& x : w) sum += (x = spreadWeight(x / top));
    for (std::size_t k = 0; k < nb.size(); ++k) {
      const std::uint32_t u = nb[k];
      nb[k] = rank[u];
      w[k] = kSpread * w[k] / sum + (1.0 - kSpread) * ((u == ba ? sa : 0.0) + (u == bb ? sb : 0.0)) / (sa + sb);
    }
  };

  std::vector<Receivers> out(n);
  // In vertex order (neighbours lie close in memory), each written to its rank's slot.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<std::uint32_t> nb;
    std::vector<double> w;
    std::vector<std::uint32_t> pick;
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      const std::uint32_t r = rank[v];
      lower(std::uint32_t(v), r, nb, w);
      Receivers& out_r = out[r];
      out_r.to.fill(kNone);
      out_r.share.fill(0.0f);
      pick.resize(nb.size());
      for (std::uint32_t k = 0; k < nb.size(); ++k) pick[k] = k;
      if (nb.size() > std::size_t(kReceivers)) {  // the largest shares, ties by rank
        std::partial_sort(pick.begin(), pick.begin() + kReceivers, pick.end(), [&](std::uint32_t a, std::uint32_t b) {
          return w[a] > w[b] || (w[a] == w[b] && nb[a] < nb[b]);
        });
        pick.resize(kReceivers);
      }
      double kept = 0;
      for (std::uint32_t k : pick) kept += w[k];
      for (std::size_t k = 0; k < pick.size(); ++k)
        out_r.to[k] = nb[pick[k]], out_r.share[k] = float(w[pick[k]] / kept);
    }
  });
  return out;
}

// R: the exposure age (history[0]), except that a rockfall scar is as young as its fall.
double exposureAge(const std::array<float, 3>& history) {
  return std::min(std::clamp(double(history[0]), 0.0, 1.0), 1.0 - std::clamp(double(history[1]), 0.0, 1.0));
}

double varnishAmount(double aired) {
  return kVarnishAmount * std::pow(aired, kVarnishExponent);
}

// Stain is laid down along the path the water takes, not at a point: `values` (by rank, two per
// vertex) averaged along the flow with weights exp(−distance / length), distance measured along
// the path (each vertex's step its spacing, `spacing`, by rank), kDepositPasses times. Each pass
// is two serial sweeps, as the water goes: down the flow, each vertex takes the water-weighted
// mean of what its givers hold; then up it, of what its receivers hold; the two one-sided means
// make the two-sided one. A drip leaves the surface: nothing is averaged across it.
void alongFlow(std::vector<std::array<double, 2>>& values, const std::vector<Receivers>& routing,
               const std::vector<char>& drips, const std::vector<double>& spacing, double length) {
  using Pair = std::array<double, 2>;
  const std::size_t n = routing.size();
  if (n == 0 || !(length > 0)) return;
  // The givers of each rank (ranks above it, increasing) and their shares.
  std::vector<std::size_t> start(n + 1, 0);
  for (std::size_t r = 0; r < n; ++r)
    for (int k = 0; k < kReceivers && routing[r].to[k] != kNone; ++k)
      if (!drips[r]) ++start[routing[r].to[k] + 1];
  for (std::size_t r = 0; r < n; ++r) start[r + 1] += start[r];
  std::vector<std::uint32_t> from(start[n]);
  std::vector<float> share(start[n]);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t r = 0; r < n; ++r)
      for (int k = 0; k < kReceivers && routing[r].to[k] != kNone; ++k)
        if (!drips[r]) {
          const std::size_t at = fill[routing[r].to[k]]++;
          from[at] = std::uint32_t(r), share[at] = routing[r].share[k];
        }
  }
  std::vector<double> keep(n);  // each step's weight on what came before: exp(−spacing / length)
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t r) { keep[r] = std::exp(-spacing[r] / length); });
  std::vector<Pair> down(n), up(n);
  // (1 − a) x + a · (the neighbours' water-weighted mean); x where there are none.
  const auto blend = [&](std::size_t r, const Pair& sum, double weight) {
    if (!(weight > 0)) return values[r];
    const double a = keep[r];
    return Pair{(1.0 - a) * values[r][0] + a * sum[0] / weight, (1.0 - a) * values[r][1] + a * sum[1] / weight};
  };
  for (int pass = 0; pass < kDepositPasses; ++pass) {
    for (std::size_t r = 0; r < n; ++r) {  // down the flow: givers first
      Pair sum{0, 0};
      double weight = 0;
      for (std::size_t k = start[r]; k < start[r + 1]; ++k) {
        const Pair& g = down[from[k]];
        sum[0] += share[k] * g[0], sum[1] += share[k] * g[1], weight += share[k];
      }
      down[r] = blend(r, sum, weight);
    }
    for (std::size_t r = n; r-- > 0;) {  // up the flow: receivers first
      Pair sum{0, 0};
      double weight = 0;
      if (!drips[r])
        for (int k = 0; k < kReceivers && routing[r].to[k] != kNone; ++k) {
          const Pair& g = up[routing[r].to[k]];
          const double w = routing[r].share[k];
          sum[0] += w * g[0], sum[1] += w * g[1], weight += w;
        }
      up[r] = blend(r, sum, weight);
    }
    // Σ_k (1 − a) a^|k| x_k over both sides, normalised by its weights (1 + a).
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t r) {
      const double a = keep[r];
      for (int c = 0; c < 2; ++c) values[r][c] = (down[r][c] + up[r][c] - (1.0 - a) * values[r][c]) / (1.0 + a);
    });
  }
}

// The damp band at a distance (voxels) from where the water is: exp(−distance / kBand), less
// its value at `reach` so that it comes to 0 there, where the search for the water stops.
double fade(double distance, double reach) {
  const double edge = std::exp(-reach / kBand);
  return std::max(0.0, std::exp(-distance / kBand) - edge) / (1.0 - edge);
}

float channel(double strength, double amount) {
  return float(std::clamp(strength * amount, 0.0, 1.0));
}

void lookRock(SurfaceMesh& m, const SurfaceLookParams& params, const GridView& grid) {
  const std::size_t n = m.positions.size();
  const double h = grid.h();
  const auto tris = m.quads.empty() ? std::vector<std::array<std::uint32_t, 3>>() : allTriangles(m);
  const auto& triangles = m.quads.empty() ? m.triangles : tris;
  const VertexFaces faces(triangles, n);
  const std::vector<double> area = vertexAreas(m, triangles, faces);

  const Drainage drain = drainage(m, faces, triangles, h, grid.ground());
  const std::vector<std::uint32_t>& rank = drain.rank;
  // Rain: the vertex's area seen from above, where the sky is open over it.
  std::vector<double> sky(n);
  std::vector<double> flow(n);  // by rank
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    const Vec3d p = toVec3d(m.positions[v]), nrm = toVec3d(m.normals[v]);
    sky[v] = grid.skyVisibility(p, nrm);
    flow[rank[v]] = area[v] * std::max(nrm[2], 0.0) * sky[v];
  });

  // Runoff, last out of the flood first: each passes on all it holds (its rain and what it was
  // given).
  const std::vector<std::uint32_t> drip = dripTargets(m, h);
  const std::vector<Receivers> routing = route(m, faces, triangles, drain, drip);
  std::vector<char> drip_given(n);  // by rank: its water drips (not along the surface)
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) { drip_given[rank[v]] = m.normals[v][2] < kShedNz; });
  for (std::size_t r = 0; r < n; ++r) {
    const double f = flow[r];
    if (f <= 0) continue;
    const Receivers& to = routing[r];
    for (int k = 0; k < kReceivers && to.to[k] != kNone; ++k) flow[to.to[k]] += f * to.share[k];
  }

  // Specific catchment, voxels: the rain area upstream over the stream's width (about the vertex
  // spacing, the square root of its area), so that the same runoff reads the same on a coarse
  // mesh and a fine one. By rank.
  std::vector<double> spacing(n), catchment(n), aired(n);
  std::vector<std::array<double, 2>> water(n);  // by rank: how wet (0..1), and what it lays down
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    const std::size_t r = rank[v];
    spacing[r] = std::sqrt(area[v]);
    catchment[r] = flow[r] / ((spacing[r] + 1e-9 * h) * h);
    const double wet = 1.0 - std::exp(-catchment[r] / kStainLength);
    // The share of the run the face spent open to the air: its age (a scar's from its fall), less
    // the time it lay against colluvium (both are shares of the run; a voxel with a face on
    // colluvium keeps its others in the air, so only kBuriedShare of that time counts).
    const auto& hist = m.history[v];
    aired[r] = std::max(0.0, exposureAge(hist) - kBuriedShare * std::clamp(double(hist[2]), 0.0, 1.0));
    // What the water lays down where it runs (on steep rock, below): the streak's stain, darker
    // the longer the face has stood, and the desert varnish that forms in streaks.
    water[r][0] = wet;
    water[r][1] = wet * (params.stain * kStainAmount * (kStainFresh + (1.0 - kStainFresh) * aired[r]) +
                         params.varnish * varnishAmount(aired[r]) * (1.0 - kVarnishOffStreak));
  });
  alongFlow(water, routing, drip_given, spacing, kDepositLength * h);

  m.look.resize(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    const std::size_t rk = rank[v];
    const Vec3d p = toVec3d(m.positions[v]);
    const Vec3d nrm = toVec3d(m.normals[v]);
    const double nz = std::clamp(nrm[2], -1.0, 1.0);
    const double steep = nz >= 0 ? 1.0 - nz * nz : 1.0;
    // R: exposure age; a scar is as young as its fall.
    const double r = exposureAge(m.history[v]);
    // What the water carries is laid down only where water runs: not on a dry face upstream of
    // where a drip lands.
    const double runs = std::min(1.0, (1.0 - std::exp(-catchment[rk] / kStainLength)) / kRunning);
    // Streaks where water runs over steep rock; a flat top, however wet, stays clean.
    const double streak = steep * runs * water[rk][0];
    // G: what the water laid down there, and the varnish every face gathers in the open.
    const double g = steep * runs * water[rk][1] + params.varnish * varnishAmount(aired[rk]) * kVarnishOffStreak;
    // B: the damp foot (capillary rise from wet colluvium or ground, and the covered skin), and
    // overhangs the rain never dries and the sun never reaches.
    const double foot = std::max(fade(grid.heightAboveWet(p, nrm) / h, kBandReach),
                                 m.colluvium.empty() ? 0.0 : std::clamp(double(m.colluvium[v]), 0.0, 1.0));
    const double overhang = 0.4 * std::clamp((-nz - 0.3) / 0.7, 0.0, 1.0) * (1.0 - sky[v]);
    const double b = 0.8 * foot + overhang;
    // A: dust on ledges and in hollows that open upwards, washed off where streams run (a
    // sheltered ledge keeps it: dust does not need the sky).
    const double up = std::max(nz, 0.0);
    const double concave = m.curvature.empty() ? 0.0 : std::clamp(2.0 * (0.5 - double(m.curvature[v])), 0.0, 1.0);
    const double settle = std::max(up * up * up * up, concave * std::min(2.0 * up, 1.0));
    // Running water washes; on a dead flat it only seeps (and the way it takes there is the
    // flood's, not a real channel), so the wash fades with the slope.
    const double washed = std::max(streak, std::sqrt(steep) * (1.0 - std::exp(-catchment[rk] / kWashLength)));
    const double a = 0.8 * settle * (1.0 - washed);

    m.look[v] = {float(r), channel(1.0, g), channel(params.moisture, b), channel(params.dust, a)};
  });
}

// The colluvium surface: no history (R 0, G 0); damp where it meets the rock and at its own foot
// on the ground, half the rock's band; no dust: it is itself the fine debris, and a dust tint on
// it would only repeat its own colour.
void lookColluvium(SurfaceMesh& m, const SurfaceLookParams& params, const GridView& grid) {
  const std::size_t n = m.positions.size();
  const double h = grid.h();
  m.look.resize(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    const Vec3d p = toVec3d(m.positions[v]);
    const double to_ground = grid.ground() ? std::max(p[2], 0.0) : std::numeric_limits<double>::infinity();
    const double b = 0.5 * std::max(fade(grid.distanceToRock(p) / h, kContactReach), fade(to_ground / h, kBandReach));
    m.look[v] = {0.0f, 0.0f, channel(params.moisture, b), 0.0f};
  });
}

}  // namespace

void makeSurfaceLook(AssetMeshes& meshes, const SurfaceLookParams& params) {
  // The rock's history is the look's switch: without one (look: none) neither surface changes.
  if (meshes.rock.history.empty()) return;
  if (params.rock == nullptr) throw std::invalid_argument("makeSurfaceLook: no grid");
  SurfaceMesh& rock = meshes.rock;
  if (rock.history.size() != rock.positions.size() || rock.normals.size() != rock.positions.size())
    throw std::invalid_argument("makeSurfaceLook: the rock surface needs a history and a normal per vertex");
  const GridView grid(*params.rock);
  lookRock(rock, params, grid);
  if (!meshes.colluvium.positions.empty()) lookColluvium(meshes.colluvium, params, grid);
}

}  // namespace rockbake
