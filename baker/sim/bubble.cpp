#include "sim/bubble.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rockbake {
namespace {

// Offsets are compared against the shape with a little slack so that, e.g., a
// radius of exactly 2 voxels includes (2, 0, 0) despite rounding in r / h.
constexpr double kSlack = 1e-9;

template <typename Inside>
std::vector<Bubble::Offset> collectOffsets(const Vec3d& extent, Inside inside) {
  std::array<int, 3> reach{};
  for (int a = 0; a < 3; ++a) reach[a] = int(std::floor(extent[a] + kSlack));
  std::vector<Bubble::Offset> offsets;
  for (int dz = -reach[2]; dz <= reach[2]; ++dz)
    for (int dy = -reach[1]; dy <= reach[1]; ++dy)
      for (int dx = -reach[0]; dx <= reach[0]; ++dx)
        if (inside(dx, dy, dz)) offsets.push_back({dx, dy, dz});
  return offsets;
}

}  // namespace

Bubble makeBubbleFromOffsets(std::vector<Bubble::Offset> offsets) {
  auto byZYX = [](const Bubble::Offset& a, const Bubble::Offset& b) {
    return std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]);
  };
  std::sort(offsets.begin(), offsets.end(), byZYX);
  offsets.erase(std::unique(offsets.begin(), offsets.end()), offsets.end());
  if (!std::binary_search(offsets.begin(), offsets.end(), Bubble::Offset{0, 0, 0}, byZYX))
    throw std::invalid_argument("a bubble must contain the offset (0, 0, 0)");
  for (const auto& o : offsets)
    if (!std::binary_search(offsets.begin(), offsets.end(), Bubble::Offset{-o[0], -o[1], -o[2]}, byZYX))
      throw std::invalid_argument("a bubble must be symmetric (o in B implies -o in B)");

  if (offsets.size() < 3)
    throw std::invalid_argument("a bubble must reach beyond its centre voxel (at least one voxel in some direction)");
  Bubble bubble;
  bubble.offsets = std::move(offsets);
  for (const auto& o : bubble.offsets) {
    bubble.reach = std::max({bubble.reach, std::abs(o[0]), std::abs(o[1]), std::abs(o[2])});
    // Offsets are sorted by (dz, dy, dx): a run continues while x steps by one.
    auto& rows = bubble.rows;
    if (!rows.empty() && rows.back().dy == o[1] && rows.back().dz == o[2] && rows.back().x_max + 1 == o[0])
      rows.back().x_max = o[0];
    else
      rows.push_back({o[1], o[2], o[0], o[0]});
  }
  double sum = 0.0;
  for (int axis = 0; axis < 6; ++axis) sum += flatFaceAlpha(bubble, axis);
  bubble.alpha_flat = sum / 6.0;
  return bubble;
}

Bubble makeSphereBubble(double r) {
  return makeBubbleFromOffsets(
      collectOffsets({r, r, r}, [r](int x, int y, int z) { return double(x * x + y * y + z * z) <= r * r + kSlack; }));
}

Bubble makeEllipsoidBubble(const Vec3d& radii) {
  return makeBubbleFromOffsets(collectOffsets(radii, [&radii](int x, int y, int z) {
    double q = (x / radii[0]) * (x / radii[0]) + (y / radii[1]) * (y / radii[1]) + (z / radii[2]) * (z / radii[2]);
    return q <= 1.0 + kSlack;
  }));
}

Bubble makeBoxBubble(const Vec3d& half) {
  return makeBubbleFromOffsets(collectOffsets(half, [](int, int, int) { return true; }));
}

double flatFaceAlpha(const Bubble& bubble, int axis) {
  // The voxel sits on the solid side; cells strictly beyond the face are air.
  const int component = axis / 2;
  const int sign = (axis % 2 == 0) ? 1 : -1;
  std::size_t air = 0;
  for (const auto& o : bubble.offsets)
    if (sign * o[component] > 0) ++air;
  return double(air) / double(bubble.offsets.size());
}

namespace {

void flatten(const BubbleSpec& spec, double h, double weight, std::vector<BubbleEstimator::Member>& out) {
  const Vec3d e{spec.extents[0] / h, spec.extents[1] / h, spec.extents[2] / h};
  switch (spec.kind) {
    case BubbleSpec::Kind::Sphere:
      out.push_back({makeSphereBubble(e[0]), weight});
      return;
    case BubbleSpec::Kind::Ellipsoid:
      out.push_back({makeEllipsoidBubble(e), weight});
      return;
    case BubbleSpec::Kind::Box:
      out.push_back({makeBoxBubble(e), weight});
      return;
    case BubbleSpec::Kind::Collection: {
      double total = 0.0;
      for (const auto& m : spec.members) total += m.weight;
      for (const auto& m : spec.members) flatten(m.bubble, h, weight * m.weight / total, out);
      return;
    }
  }
}

}  // namespace

int bubbleReach(const BubbleSpec& spec, double h) {
  if (spec.kind == BubbleSpec::Kind::Collection) {
    int reach = 0;
    for (const auto& m : spec.members) reach = std::max(reach, bubbleReach(m.bubble, h));
    return reach;
  }
  const int axes = spec.kind == BubbleSpec::Kind::Sphere ? 1 : 3;
  double extent = 0.0;
  for (int a = 0; a < axes; ++a) extent = std::max(extent, spec.extents[std::size_t(a)]);
  return int(std::floor(extent / h + kSlack));
}

BubbleEstimator makeBubbleEstimator(const BubbleSpec& spec, double h) {
  BubbleEstimator estimator;
  flatten(spec, h, 1.0, estimator.members);
  for (const auto& m : estimator.members) estimator.reach = std::max(estimator.reach, m.bubble.reach);
  return estimator;
}

}  // namespace rockbake
