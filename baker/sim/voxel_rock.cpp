#include "sim/voxel_rock.h"

#include <algorithm>
#include <cmath>

namespace rockbake {
namespace {

// Largest integer offset a bubble reaches along any axis, in voxels.
int bubbleReach(const BubbleSpec& spec, double h) {
  if (spec.kind == BubbleSpec::Kind::Collection) {
    int reach = 0;
    for (const auto& m : spec.members) reach = std::max(reach, bubbleReach(m.bubble, h));
    return reach;
  }
  const int axes = spec.kind == BubbleSpec::Kind::Sphere ? 1 : 3;
  double extent = 0.0;
  for (int a = 0; a < axes; ++a) extent = std::max(extent, spec.extents[a]);
  return int(std::floor(extent / h + 1e-9));
}

}  // namespace

GridLayout computeGridLayout(const Preset& preset) {
  GridLayout g;
  const Vec3d& size = preset.grid.size;
  g.h = std::max({size[0], size[1], size[2]}) / double(preset.grid.resolution);
  int reach = 0;
  for (const auto& band : preset.bubbles) reach = std::max(reach, bubbleReach(band.bubble, g.h));
  g.margin = reach + 1;
  const auto cells = [&](double extent) { return std::max(1, int(std::lround(extent / g.h))); };
  g.nx = cells(size[0]) + 2 * g.margin;
  g.ny = cells(size[1]) + 2 * g.margin;
  g.nz = cells(size[2]) + g.margin;
  g.origin = {-g.margin * g.h, -g.margin * g.h, 0.0};
  g.domain_height = size[2];
  g.ground = preset.grid.ground;
  return g;
}

std::uint64_t estimateSimulationBytes(const GridLayout& layout) {
  const std::uint64_t cells = layout.cellCount();
  const std::uint64_t rows = std::uint64_t(layout.ny) * std::uint64_t(layout.nz);
  // Rock lies inside the domain: the grid less its margin on four sides and the top.
  const auto inner = [&](int n, int sides) { return std::uint64_t(std::max(0, n - sides * layout.margin)); };
  const std::uint64_t domain = inner(layout.nx, 2) * inner(layout.ny, 2) * inner(layout.nz, 1);
  const std::uint64_t apron = std::uint64_t(layout.margin);
  const std::uint64_t field_bits = (layout.nx + 2 * apron + 128) * (layout.ny + 2 * apron) * (layout.nz + 2 * apron);
  // material (1 byte a cell); integrity and durability (4 + 4 bytes a rock
  // cell, at most the domain, plus a span header per row for each); the air
  // field; five bit planes (exposed, colluvium, and rockfall's visited,
  // removed and clustered marks); work lists for the exposed voxels, at most
  // about a tenth of the domain at once (cell, flag and counts: 16 bytes).
  return cells + domain * 8 + rows * 2 * 32 + field_bits / 8 + cells * 5 / 8 + domain / 10 * 16;
}

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

}  // namespace rockbake
