#include "clasts/clast_blocks.h"

#include <cmath>

#include "core/hash.h"

namespace rockbake {
namespace {

constexpr std::uint64_t kPurpose = purposeId("clast block");

double draw(std::uint64_t seed, int index, int what) {
  return unitInterval(counterHash(seed, kPurpose, std::uint64_t(index), std::uint64_t(what)));
}

}  // namespace

ClastBlock drawClastBlock(std::uint64_t seed, int index, double length) {
  ClastBlock block;
  // Intermediate and short axes as fractions of the long one: 0.55–0.95 and 0.35–0.8 of it, the
  // short never above the intermediate, spans all four of Zingg's classes.
  const double b = 0.55 + 0.4 * draw(seed, index, 0);
  const double c = std::min(b, 0.35 + 0.45 * draw(seed, index, 1));
  block.half_extents = {0.5 * length, 0.5 * length * b, 0.5 * length * c};
  // Two to four corners knocked off: a cut's normal points into an octant, its plane 55–90 % of
  // the way from the centre to that corner's support.
  const int cuts = 2 + int(3 * draw(seed, index, 2));
  for (int k = 0; k < cuts; ++k) {
    const int octant = int(8 * draw(seed, index, 10 + 4 * k));
    Vec3d n{};
    for (int axis = 0; axis < 3; ++axis) {
      const double sign = (octant >> axis) & 1 ? 1.0 : -1.0;
      n[axis] = sign * (0.3 + draw(seed, index, 11 + 4 * k + axis));
    }
    n = normalised(n, Vec3d{0, 0, 1});
    const Vec3d& h = block.half_extents;
    const double support = std::abs(n[0]) * h[0] + std::abs(n[1]) * h[1] + std::abs(n[2]) * h[2];
    block.cuts.push_back({n, support * (0.55 + 0.35 * draw(seed, index, 30 + k))});
  }
  return block;
}

VoxelRock voxelizeClastBlock(const ClastBlock& block, const GridLayout& layout, float durability) {
  VoxelRock rock;
  rock.layout = layout;
  rock.material.assign(layout.cellCount(), Material::Air);
  const Vec3d centre{layout.origin[0] + 0.5 * layout.nx * layout.h, layout.origin[1] + 0.5 * layout.ny * layout.h,
                     layout.origin[2] + 0.5 * layout.nz * layout.h};
  const Vec3d& h = block.half_extents;
  for (int z = 0; z < layout.nz; ++z)
    for (int y = 0; y < layout.ny; ++y)
      for (int x = 0; x < layout.nx; ++x) {
        const Vec3d p = sub(layout.center(x, y, z), centre);
        bool inside = std::abs(p[0]) <= h[0] && std::abs(p[1]) <= h[1] && std::abs(p[2]) <= h[2];
        for (const ClastBlock::Cut& cut : block.cuts) inside = inside && dot(cut.normal, p) <= cut.offset;
        if (inside) rock.material[layout.index(x, y, z)] = Material::Rock;
      }
  resetRockValues(rock);
  for (std::size_t c = 0; c < rock.material.size(); ++c)
    if (rock.material[c] == Material::Rock) rock.durability.set(c, durability);
  return rock;
}

}  // namespace rockbake
