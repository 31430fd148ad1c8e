#include "texture/pack_charts.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#define STB_RECT_PACK_IMPLEMENTATION
#define STBRP_STATIC
#include <stb/stb_rect_pack.h>

namespace rockbake {
namespace {

using UV = std::array<double, 2>;

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

struct Oriented {
  double cos = 1, sin = 0;  // rotation applied to the chart
  double width = 0, height = 0;
  UV low{0, 0};  // the rotated chart's lower corner
};

// The rotation that makes the chart's bounding rectangle smallest, width >= height.
Oriented orient(const std::vector<UV>& uv) {
  const std::vector<UV> hull = convexHull(uv);
  Oriented best;
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
      best = {c, s, hi[0] - lo[0], hi[1] - lo[1], {lo[0], lo[1]}};
    }
  };
  tryAngle(1, 0);
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const UV& a = hull[i];
    const UV& b = hull[(i + 1) % hull.size()];
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (len > 0) tryAngle((b[0] - a[0]) / len, -(b[1] - a[1]) / len);  // turns the edge onto +x
  }
  if (best.height > best.width) {  // a quarter turn, (x, y) → (−y, x)
    best = {-best.sin, best.cos, best.height, best.width, {-(best.low[1] + best.height), best.low[0]}};
  }
  return best;
}

struct Packing {
  bool ok = false;
  std::vector<stbrp_rect> rects;
};

Packing tryPack(const std::vector<Oriented>& charts, double density, int size, int padding) {
  Packing p;
  p.rects.resize(charts.size());
  for (std::size_t i = 0; i < charts.size(); ++i) {
    const double w = std::ceil(density * charts[i].width) + padding + 1;
    const double h = std::ceil(density * charts[i].height) + padding + 1;
    if (w > size || h > size) return p;
    p.rects[i] = {int(i), int(w), int(h), 0, 0, 0};
  }
  std::vector<stbrp_node> nodes(std::size_t(size) + 1);
  stbrp_context context;
  stbrp_init_target(&context, size, size, nodes.data(), int(nodes.size()));
  stbrp_setup_heuristic(&context, STBRP_HEURISTIC_Skyline_BL_sortHeight);
  p.ok = stbrp_pack_rects(&context, p.rects.data(), int(p.rects.size())) == 1;
  return p;
}

}  // namespace

double packCharts(std::vector<std::vector<UV>>& charts, int size, int padding) {
  if (charts.empty()) return 0.0;
  std::vector<Oriented> oriented(charts.size());
  double area = 0;
  for (std::size_t i = 0; i < charts.size(); ++i) {
    oriented[i] = orient(charts[i]);
    area += oriented[i].width * oriented[i].height;
  }
  // No density above this fits (the rectangles alone would cover the map); bisect below it.
  double high = area > 0 ? double(size) / std::sqrt(area) : 1.0, low = 0;
  Packing best = tryPack(oriented, low, size, padding);
  if (!best.ok)
    throw std::runtime_error("cannot pack " + std::to_string(charts.size()) + " UV charts into a " +
                             std::to_string(size) + "² map with " + std::to_string(padding) +
                             "-texel gutters (raise texture.size or lower texture.padding)");
  for (int i = 0; i < 30 && high - low > 1e-4 * high; ++i) {
    const double mid = 0.5 * (low + high);
    Packing p = tryPack(oriented, mid, size, padding);
    if (p.ok) {
      low = mid;
      best = std::move(p);
    } else {
      high = mid;
    }
  }
  const double density = low;
  const double offset = 0.5 * (padding + 1);
  for (std::size_t i = 0; i < charts.size(); ++i) {
    const Oriented& o = oriented[i];
    const stbrp_rect& r = best.rects[i];
    for (UV& p : charts[i]) {
      const double x = o.cos * p[0] - o.sin * p[1] - o.low[0], y = o.sin * p[0] + o.cos * p[1] - o.low[1];
      // Texel rows run down: the chart's up is the image's up.
      p = {(r.x + offset + density * x) / size, (r.y + offset + density * (o.height - y)) / size};
    }
  }
  return density;
}

}  // namespace rockbake
