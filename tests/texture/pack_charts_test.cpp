// Chart packing (texture/pack_charts.h): charts land in the unit square, never overlap, keep
// `padding` empty texels between them, and small charts fill the holes big ones leave (inside
// a concave chart's cavity, reachable only through a slit narrower than they are).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "texture/pack_charts.h"

namespace rockbake {
namespace {

// Axis-aligned rectangles, two triangles each (counter-clockwise), as one chart.
PackChart rectangles(const std::vector<std::array<double, 4>>& boxes) {  // x0, y0, x1, y1
  PackChart c;
  for (const auto& b : boxes) {
    const auto v = std::uint32_t(c.uv.size());
    c.uv.insert(c.uv.end(), {{b[0], b[1]}, {b[2], b[1]}, {b[2], b[3]}, {b[0], b[3]}});
    c.triangles.push_back({v, v + 1, v + 2});
    c.triangles.push_back({v, v + 2, v + 3});
  }
  return c;
}

// A square ring 40 units wide, 5 thick, with a 3-unit slit in one side: its 30-unit cavity is
// open to the outside only through the slit.
PackChart slitRing() {
  return rectangles({{0, 0, 40, 5}, {0, 35, 18.5, 40}, {21.5, 35, 40, 40}, {0, 5, 5, 35}, {35, 5, 40, 35}});
}

struct Packed {
  double use = 0;             // share of the map's texels covered
  std::size_t contested = 0;  // texels whose centre two charts cover
  std::size_t too_close = 0;  // covered texels with another chart's within `padding`
  bool inside_unit_square = true;
};

// Rasterises the packed charts (texel centres inside a triangle) and checks them.
Packed check(const std::vector<PackChart>& charts, int size, int padding) {
  constexpr std::int32_t kEmpty = -1;
  std::vector<std::int32_t> owner(std::size_t(size) * size, kEmpty);
  Packed p;
  std::size_t covered = 0;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    for (const auto& uv : charts[c].uv) p.inside_unit_square &= uv[0] >= 0 && uv[0] <= 1 && uv[1] >= 0 && uv[1] <= 1;
    std::vector<char> mine(owner.size(), 0);
    for (const auto& t : charts[c].triangles) {
      const auto &a = charts[c].uv[t[0]], &b = charts[c].uv[t[1]], &d = charts[c].uv[t[2]];
      const auto edge = [](const std::array<double, 2>& p, const std::array<double, 2>& q, double x, double y) {
        return (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]);
      };
      const int x0 = std::max(0, int(std::min({a[0], b[0], d[0]}) * size) - 1),
                x1 = std::min(size - 1, int(std::max({a[0], b[0], d[0]}) * size) + 1);
      const int y0 = std::max(0, int(std::min({a[1], b[1], d[1]}) * size) - 1),
                y1 = std::min(size - 1, int(std::max({a[1], b[1], d[1]}) * size) + 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double u = (x + 0.5) / size, v = (y + 0.5) / size;
          const double e0 = edge(a, b, u, v), e1 = edge(b, d, u, v), e2 = edge(d, a, u, v);
          if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0)) mine[std::size_t(y) * size + x] = 1;
        }
    }
    for (std::size_t i = 0; i < owner.size(); ++i) {
      if (!mine[i]) continue;
      if (owner[i] != kEmpty)
        ++p.contested;
      else
        owner[i] = std::int32_t(c), ++covered;
    }
  }
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::int32_t t = owner[std::size_t(y) * size + x];
      if (t == kEmpty) continue;
      bool close = false;
      for (int dy = -padding; dy <= padding && !close; ++dy)
        for (int dx = -padding; dx <= padding && !close; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= size || ny >= size) continue;
          const std::int32_t u = owner[std::size_t(ny) * size + nx];
          close = u != kEmpty && u != t;
        }
      p.too_close += close;
    }
  p.use = double(covered) / double(owner.size());
  return p;
}

TEST(PackCharts, SmallChartsFillTheCavitiesOfConcaveOnes) {
  // Four slit rings and, per ring, four 12-unit squares: wider than a slit, so only a packer
  // that places charts in holes (not just on the horizon of what is packed) puts them inside.
  std::vector<PackChart> charts;
  for (int i = 0; i < 4; ++i) charts.push_back(slitRing());
  for (int i = 0; i < 16; ++i) charts.push_back(rectangles({{0, 0, 12, 12}}));
  const int size = 256, padding = 2;
  const double density = packCharts(charts, size, padding);
  EXPECT_GT(density, 0.0);
  const Packed p = check(charts, size, padding);
  EXPECT_TRUE(p.inside_unit_square);
  EXPECT_EQ(p.contested, 0u);
  EXPECT_EQ(p.too_close, 0u);
  // Rings and squares cover 5,044 of the 6,400 units² the rings span, the squares inside the
  // cavities (59 % of the map). Packed beside the rings, as when a column's footprint spans a
  // ring's cavity or only the horizon of what is packed is searched, they leave 43 %.
  EXPECT_GT(p.use, 0.5);
}

TEST(PackCharts, JaggedChartsKeepTheirGutters) {
  // Combs: teeth of different lengths interlock when charts nest into each other.
  std::vector<PackChart> charts;
  for (int i = 0; i < 12; ++i) {
    std::vector<std::array<double, 4>> boxes{{0, 0, 30, 4}};
    for (int k = 0; k < 5; ++k) boxes.push_back({6.0 * k, 4, 6.0 * k + 3, 4 + 3.0 * ((i + k) % 4 + 1)});
    charts.push_back(rectangles(boxes));
  }
  for (int padding : {1, 4, 8}) {
    std::vector<PackChart> packed = charts;
    packCharts(packed, 256, padding);
    const Packed p = check(packed, 256, padding);
    EXPECT_TRUE(p.inside_unit_square) << "padding " << padding;
    EXPECT_EQ(p.contested, 0u) << "padding " << padding;
    EXPECT_EQ(p.too_close, 0u) << "padding " << padding;
  }
}

// Many small charts of assorted sizes and shapes (squares, L shapes, thin bars), from a fixed
// linear congruential sequence.
std::vector<PackChart> smallCharts(int count) {
  std::vector<PackChart> charts;
  std::uint32_t state = 12345;
  const auto next = [&](double lo, double hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * double(state >> 8) / double(1u << 24);
  };
  for (int i = 0; i < count; ++i) {
    const double a = next(2, 8), b = next(2, 8);
    switch (i % 3) {
      case 0:
        charts.push_back(rectangles({{0, 0, a, b}}));
        break;
      case 1:
        charts.push_back(rectangles({{0, 0, a, 1.5}, {0, 1.5, 1.5, 1.5 + b}}));
        break;
      default:
        charts.push_back(rectangles({{0, 0, a + b, 1}}));
        break;
    }
  }
  return charts;
}

TEST(PackCharts, SearchCostsLessThanALiftPerPositionHoweverDeepThePile) {
  // A chart tried at a column starts above every gap too short for it there and is lifted past
  // a taken texel straight to the next gap long enough, so however deep the pile beneath, a
  // position costs less than a lift and a gap looked at, on average; climbing run by run from
  // the lowest free row through every chart beneath costs a lift per chart in the pile.
  const auto work = [](int count, int size) {
    std::vector<PackChart> charts = smallCharts(count);
    PackWork w;
    packCharts(charts, size, 2, &w);
    const Packed p = check(charts, size, 2);
    EXPECT_EQ(p.contested, 0u) << count << " charts";
    EXPECT_EQ(p.too_close, 0u) << count << " charts";
    EXPECT_TRUE(p.inside_unit_square) << count << " charts";
    return w;
  };
  const PackWork few = work(300, 256), many = work(1200, 512);
  ASSERT_GT(few.positions, 0u);
  ASSERT_GT(many.positions, 0u);
  const double lifts_few = double(few.lifts) / double(few.positions);
  const double lifts_many = double(many.lifts) / double(many.positions);
  const double gaps_few = double(few.gaps_passed) / double(few.positions);
  const double gaps_many = double(many.gaps_passed) / double(many.positions);
  std::printf("lifts per position %.3f → %.3f, gaps per position %.3f → %.3f\n", lifts_few, lifts_many, gaps_few,
              gaps_many);
  EXPECT_LT(lifts_few, 1.0);
  EXPECT_LT(lifts_many, 1.0);
  EXPECT_LT(gaps_few, 1.0);
  EXPECT_LT(gaps_many, 1.0);
  // Every chart is tried at every eighth column in four turns, then at the columns near the
  // best: the positions per chart follow the map's width alone.
  EXPECT_LE(double(many.positions) / double(many.charts), 4.0 * (512 / 8 + 1) + 14);
}

}  // namespace
}  // namespace rockbake
