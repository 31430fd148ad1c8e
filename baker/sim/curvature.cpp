#include "sim/curvature.h"

#include <atomic>
#include <bit>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

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
  // Layers in parallel: each row's bits live in words of their own.
  tbb::parallel_for(0, g.nz, [&](int z) {
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] != Material::Air) setAir(x, y, z, false);
  });
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

static_assert(std::endian::native == std::endian::little, "the row loads read words as little-endian bytes");

inline std::uint64_t loadWord(const unsigned char* p) {
  std::uint64_t w;
  std::memcpy(&w, p, sizeof w);
  return w;
}

// The portable run: one load per piece, each voxel's window shifted out of it.
void countRunPortable(const AirField::BoundBubble& b, const unsigned char* base, int phase, const std::uint8_t* dx,
                      int n, int* out) {
  const std::int32_t* offset = b.offsets(std::size_t(phase));
  const std::uint64_t* mask = b.masks(std::size_t(phase));
  int acc[AirField::kRunWidth] = {};
  for (std::size_t i = 0; i < b.pieces; ++i) {
    const std::uint64_t w = loadWord(base + offset[i]);
    for (int k = 0; k < n; ++k) acc[k] += std::popcount((w >> dx[k]) & mask[i]);
  }
  for (int k = 0; k < n; ++k) out[k] = acc[k];
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ROCKBAKE_HAVE_AVX512_PATH 1
// Eight lanes, one per voxel of the run: the piece's word is broadcast,
// shifted by each voxel's dx, masked and counted with VPOPCNTQ.
__attribute__((target("avx512f,avx512vpopcntdq"))) void countRunAvx512(const AirField::BoundBubble& b,
                                                                       const unsigned char* base, int phase,
                                                                       const std::uint8_t* dx, int n, int* out) {
  const std::int32_t* offset = b.offsets(std::size_t(phase));
  const std::uint64_t* mask = b.masks(std::size_t(phase));
  std::uint64_t lane_dx[AirField::kRunWidth] = {};
  for (int k = 0; k < n; ++k) lane_dx[k] = dx[k];
  const __m512i shift = _mm512_loadu_si512(lane_dx);
  // maskz forms (all lanes on): the plain ones trip GCC 12's -Wmaybe-uninitialized.
  const __mmask8 all = 0xFF;
  __m512i acc0 = _mm512_setzero_si512(), acc1 = _mm512_setzero_si512();
  std::size_t i = 0;
  for (; i + 1 < b.pieces; i += 2) {
    const __m512i w0 = _mm512_set1_epi64(std::int64_t(loadWord(base + offset[i])));
    const __m512i w1 = _mm512_set1_epi64(std::int64_t(loadWord(base + offset[i + 1])));
    const __m512i m0 = _mm512_set1_epi64(std::int64_t(mask[i]));
    const __m512i m1 = _mm512_set1_epi64(std::int64_t(mask[i + 1]));
    acc0 = _mm512_add_epi64(acc0, _mm512_popcnt_epi64(_mm512_and_si512(_mm512_maskz_srlv_epi64(all, w0, shift), m0)));
    acc1 = _mm512_add_epi64(acc1, _mm512_popcnt_epi64(_mm512_and_si512(_mm512_maskz_srlv_epi64(all, w1, shift), m1)));
  }
  if (i < b.pieces) {
    const __m512i w0 = _mm512_set1_epi64(std::int64_t(loadWord(base + offset[i])));
    const __m512i m0 = _mm512_set1_epi64(std::int64_t(mask[i]));
    acc0 = _mm512_add_epi64(acc0, _mm512_popcnt_epi64(_mm512_and_si512(_mm512_maskz_srlv_epi64(all, w0, shift), m0)));
  }
  alignas(64) std::int64_t counts[AirField::kRunWidth];
  _mm512_store_si512(counts, _mm512_add_epi64(acc0, acc1));
  for (int k = 0; k < n; ++k) out[k] = int(counts[k]);
}

// One voxel, eight of its pieces at a time: the lanes gather eight rows'
// words (VPGATHERDQ) and count them against the pieces' masks. The tables are
// padded to a multiple of 8 pieces with empty masks.
__attribute__((target("avx512f,avx512vpopcntdq"))) int countOneAvx512(const AirField::BoundBubble& b,
                                                                      const unsigned char* base, int phase) {
  const std::int32_t* offset = b.offsets(std::size_t(phase));
  const std::uint64_t* mask = b.masks(std::size_t(phase));
  // Masked forms with a zero source: the plain ones trip GCC 12's -Wuninitialized.
  const __m512i zero = _mm512_setzero_si512();
  const __mmask8 all = 0xFF;
  __m512i acc0 = zero, acc1 = zero;
  const std::size_t stride = b.stride();
  std::size_t i = 0;
  for (; i + 16 <= stride; i += 16) {
    const __m256i o0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(offset + i));
    const __m256i o1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(offset + i + 8));
    const __m512i w0 = _mm512_mask_i32gather_epi64(zero, all, o0, base, 1);
    const __m512i w1 = _mm512_mask_i32gather_epi64(zero, all, o1, base, 1);
    acc0 = _mm512_add_epi64(acc0, _mm512_popcnt_epi64(_mm512_and_si512(w0, _mm512_loadu_si512(mask + i))));
    acc1 = _mm512_add_epi64(acc1, _mm512_popcnt_epi64(_mm512_and_si512(w1, _mm512_loadu_si512(mask + i + 8))));
  }
  if (i < stride) {
    const __m256i o0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(offset + i));
    const __m512i w0 = _mm512_mask_i32gather_epi64(zero, all, o0, base, 1);
    acc0 = _mm512_add_epi64(acc0, _mm512_popcnt_epi64(_mm512_and_si512(w0, _mm512_loadu_si512(mask + i))));
  }
  alignas(64) std::int64_t lanes[8];
  _mm512_store_si512(lanes, _mm512_add_epi64(acc0, acc1));
  return int(lanes[0] + lanes[1] + lanes[2] + lanes[3] + lanes[4] + lanes[5] + lanes[6] + lanes[7]);
}
#endif

bool cpuHasAvx512Path() {
#ifdef ROCKBAKE_HAVE_AVX512_PATH
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vpopcntdq");
#else
  return false;
#endif
}

AlphaPath initialAlphaPath() {
  const AlphaPath best = cpuHasAvx512Path() ? AlphaPath::Avx512 : AlphaPath::Portable;
  const char* forced = std::getenv("ROCKBAKE_ALPHA_PATH");
  if (!forced || !*forced || std::string_view(forced) == "auto") return best;
  if (std::string_view(forced) == "portable") return AlphaPath::Portable;
  if (std::string_view(forced) == "avx512") {
    if (best == AlphaPath::Avx512) return best;
    spdlog::warn("ROCKBAKE_ALPHA_PATH=avx512, but this CPU lacks AVX-512F/VPOPCNTDQ: counting on the portable path");
    return AlphaPath::Portable;
  }
  spdlog::warn("ROCKBAKE_ALPHA_PATH={} is not one of auto, portable, avx512: using {}", forced, alphaPathName(best));
  return best;
}

std::atomic<AlphaPath>& currentAlphaPath() {
  static std::atomic<AlphaPath> path{initialAlphaPath()};
  return path;
}

}  // namespace

const char* alphaPathName(AlphaPath path) {
  return path == AlphaPath::Avx512 ? "avx512" : "portable";
}

bool alphaPathAvailable(AlphaPath path) {
  return path == AlphaPath::Portable || cpuHasAvx512Path();
}

AlphaPath alphaPath() {
  return currentAlphaPath().load(std::memory_order_relaxed);
}

void setAlphaPath(AlphaPath path) {
  if (!alphaPathAvailable(path))
    throw std::invalid_argument(std::string("this CPU cannot count on the ") + alphaPathName(path) + " path");
  currentAlphaPath().store(path, std::memory_order_relaxed);
}

AirField::BoundBubble AirField::bind(const Bubble& bubble) const {
  if (bubble.reach > apron_) throw std::logic_error("bubble reaches beyond the air field's apron");
  BoundBubble bound;
  bound.size = int(bubble.offsets.size());
  bound.alpha_flat = bubble.alpha_flat;
  struct Piece {
    std::int64_t row_bytes;  // from the centre's row to this piece's row
    int x_min, length;
  };
  std::vector<Piece> pieces;
  for (const auto& row : bubble.rows) {
    const std::int64_t rows_away = std::int64_t(row.dz) * rows_y_ + row.dy;
    for (int x = row.x_min; x <= row.x_max; x += kMaxPiece)
      pieces.push_back({rows_away * std::int64_t(words_per_row_) * 8, x, std::min(kMaxPiece, row.x_max - x + 1)});
  }
  bound.pieces = pieces.size();
  // The padding pieces read the centre's byte through an empty mask.
  bound.byte_offset.assign(8 * bound.stride(), 0);
  bound.mask.assign(8 * bound.stride(), 0);
  for (int phase = 0; phase < 8; ++phase)
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      // The centre's bit is 8 B + phase; the piece starts at bit 8 B + phase + x_min.
      const int first = phase + pieces[i].x_min;
      const std::int64_t offset = pieces[i].row_bytes + (first >> 3);  // floor division
      if (offset < INT32_MIN || offset > INT32_MAX) throw std::length_error("air field too large for 32-bit offsets");
      bound.byte_offset[std::size_t(phase) * bound.stride() + i] = std::int32_t(offset);
      bound.mask[std::size_t(phase) * bound.stride() + i] = ((std::uint64_t(1) << pieces[i].length) - 1) << (first & 7);
    }
  return bound;
}

int AirField::countAir(const BoundBubble& bubble, int x, int y, int z) const {
  const int bit = x + x_pad_bits_;
  const unsigned char* base = reinterpret_cast<const unsigned char*>(rowWords(y, z)) + (bit >> 3);
  const std::size_t phase = std::size_t(bit & 7);
  const std::int32_t* offset = bubble.offsets(phase);
  const std::uint64_t* mask = bubble.masks(phase);
  // Two sums, so consecutive pieces do not wait on each other.
  int air0 = 0, air1 = 0;
  std::size_t i = 0;
  for (; i + 1 < bubble.pieces; i += 2) {
    air0 += std::popcount(loadWord(base + offset[i]) & mask[i]);
    air1 += std::popcount(loadWord(base + offset[i + 1]) & mask[i + 1]);
  }
  if (i < bubble.pieces) air0 += std::popcount(loadWord(base + offset[i]) & mask[i]);
  return air0 + air1;
}

void AirField::countAirRun(const BoundBubble& bubble, int x0, int y, int z, const std::uint8_t* dx, int n,
                           int* out) const {
  countAirRun(alphaPath(), bubble, x0, y, z, dx, n, out);
}

void AirField::countAirRun(AlphaPath path, const BoundBubble& bubble, int x0, int y, int z, const std::uint8_t* dx,
                           int n, int* out) const {
  const int bit = x0 + x_pad_bits_;
  const unsigned char* base = reinterpret_cast<const unsigned char*>(rowWords(y, z)) + (bit >> 3);
#ifdef ROCKBAKE_HAVE_AVX512_PATH
  if (path == AlphaPath::Avx512) {
    if (n == 1) {
      out[0] = countOneAvx512(bubble, base, bit & 7);
      return;
    }
    return countRunAvx512(bubble, base, bit & 7, dx, n, out);
  }
#else
  (void)path;
#endif
  if (n == 1) {
    out[0] = countAir(bubble, x0, y, z);
    return;
  }
  countRunPortable(bubble, base, bit & 7, dx, n, out);
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

void exposureRun(const AirField& field, const BoundEstimator& estimator, int x0, int y, int z, const std::uint8_t* dx,
                 int n, double* s) {
  for (int k = 0; k < n; ++k) s[k] = 0.0;
  int counts[AirField::kRunWidth];
  for (std::size_t i = 0; i < estimator.members.size(); ++i) {
    const auto& bubble = estimator.members[i];
    field.countAirRun(bubble, x0, y, z, dx, n, counts);
    for (int k = 0; k < n; ++k) {
      const double alpha = double(counts[k]) / double(bubble.size);
      s[k] += estimator.weights[i] * calibratedExposure(alpha, bubble.alpha_flat);
    }
  }
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
