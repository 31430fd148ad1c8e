#include "sim/curvature.h"

#include <bit>
#include <cstring>
#include <stdexcept>

namespace rockbake {

AirField::AirField(const VoxelRock& rock, int apron) : apron_(apron) {
  const GridLayout& g = rock.layout;
  x_pad_bits_ = ((apron + 63) / 64) * 64;
  rows_y_ = g.ny + 2 * apron;
  const int rows_z = g.nz + 2 * apron;
  words_per_row_ = std::size_t((x_pad_bits_ + g.nx + apron + 63) / 64);
  // Everything starts as air; the ground rows below z = 0 are solid.
  // One spare word at the end keeps 8-byte loads at the last row in bounds.
  words_.assign(words_per_row_ * std::size_t(rows_y_) * std::size_t(rows_z) + 1, ~std::uint64_t(0));
  if (g.ground) {
    for (int z = -apron; z < 0; ++z)
      for (int y = -apron; y < g.ny + apron; ++y) {
        std::uint64_t* row = rowWords(y, z);
        std::fill(row, row + words_per_row_, 0);
      }
  }
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] != Material::Air) setAir(x, y, z, false);
}

void AirField::setAir(int x, int y, int z, bool air) {
  const int bit = x + x_pad_bits_;
  std::uint64_t& word = rowWords(y, z)[bit >> 6];
  const std::uint64_t mask = std::uint64_t(1) << (bit & 63);
  word = air ? (word | mask) : (word & ~mask);
}

bool AirField::isAir(int x, int y, int z) const {
  const int bit = x + x_pad_bits_;
  return (rowWords(y, z)[bit >> 6] >> (bit & 63)) & 1u;
}

namespace {
// An unaligned 8-byte load starting at a row's first byte holds at least 57
// of its bits after the sub-byte shift.
constexpr int kMaxShortRow = 57;
static_assert(std::endian::native == std::endian::little, "the row loads read words as little-endian bytes");
}  // namespace

AirField::BoundBubble AirField::bind(const Bubble& bubble) const {
  if (bubble.reach > apron_) throw std::logic_error("bubble reaches beyond the air field's apron");
  BoundBubble bound;
  bound.size = int(bubble.offsets.size());
  bound.alpha_flat = bubble.alpha_flat;
  for (const auto& row : bubble.rows) {
    const std::ptrdiff_t rows_away = std::ptrdiff_t(row.dz) * rows_y_ + row.dy;
    const int length = row.x_max - row.x_min + 1;
    bound.short_rows = bound.short_rows && length <= kMaxShortRow;
    const std::uint64_t mask = length >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << length) - 1;
    bound.rows.push_back({rows_away * std::ptrdiff_t(words_per_row_), row.x_min, row.x_max, mask});
  }
  return bound;
}

namespace {

// Set bits of `row` in the bit range [first, last], both inclusive.
inline int popcountRange(const std::uint64_t* row, int first, int last) {
  const int w0 = first >> 6, w1 = last >> 6;
  const int lo = first & 63, hi = last & 63;
  const std::uint64_t high_mask = ~std::uint64_t(0) >> (63 - hi);
  if (w0 == w1) return std::popcount((row[w0] >> lo) & (high_mask >> lo));
  int count = std::popcount(row[w0] >> lo);
  for (int w = w0 + 1; w < w1; ++w) count += std::popcount(row[w]);
  return count + std::popcount(row[w1] & high_mask);
}

}  // namespace

int AirField::countAir(const BoundBubble& bubble, int x, int y, int z) const {
  const std::uint64_t* centre = rowWords(y, z);
  const int bit = x + x_pad_bits_;
  int air = 0;
  if (bubble.short_rows) {
    // The hot path: one unaligned load, shift, mask and popcount per row.
    for (const auto& row : bubble.rows) {
      const int first = bit + row.x_min;
      std::uint64_t bits;
      std::memcpy(&bits, reinterpret_cast<const unsigned char*>(centre + row.word_offset) + (first >> 3), sizeof bits);
      air += std::popcount((bits >> (first & 7)) & row.mask);
    }
    return air;
  }
  for (const auto& row : bubble.rows) air += popcountRange(centre + row.word_offset, bit + row.x_min, bit + row.x_max);
  return air;
}

int naiveCountAir(const VoxelRock& rock, const Bubble& bubble, int x, int y, int z) {
  const GridLayout& g = rock.layout;
  int air = 0;
  for (const auto& o : bubble.offsets) {
    const int cx = x + o[0], cy = y + o[1], cz = z + o[2];
    if (cz < 0) {
      air += g.ground ? 0 : 1;
    } else if (!g.contains(cx, cy, cz)) {
      air += 1;
    } else {
      air += rock.material[g.index(cx, cy, cz)] == Material::Air ? 1 : 0;
    }
  }
  return air;
}

BoundEstimator bindEstimator(const AirField& field, const BubbleEstimator& estimator) {
  BoundEstimator bound;
  for (const auto& m : estimator.members) {
    bound.members.push_back(field.bind(m.bubble));
    bound.weights.push_back(m.weight);
  }
  return bound;
}

double exposureAt(const AirField& field, const BoundEstimator& estimator, int x, int y, int z) {
  double s = 0.0;
  for (std::size_t i = 0; i < estimator.members.size(); ++i) {
    const auto& bubble = estimator.members[i];
    const double alpha = double(field.countAir(bubble, x, y, z)) / double(bubble.size);
    s += estimator.weights[i] * calibratedExposure(alpha, bubble.alpha_flat);
  }
  return s;
}

}  // namespace rockbake
