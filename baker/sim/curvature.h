// Exact bubble counts α and calibrated exposure s (docs/model.md §3).
//
// AirField keeps one bit per cell (1 = air) in rows along x, with an apron of
// cells around the grid whose bits follow docs/model.md §3: air beyond the sides and
// the top, solid below the ground (air when grid.ground is false). Colluvium
// counts as solid. Counting a bubble is then one masked popcount per bubble
// row instead of one lookup per offset: O(R²) per voxel, not O(R³), and it
// equals the naive loop exactly. Rows are cut into pieces of at most 50 cells
// so that every piece is one unaligned 64-bit load, whatever the bubble size.
#pragma once

#include <cstdint>
#include <vector>

#include "core/voxel_rock.h"
#include "sim/bubble.h"

namespace rockbake {

// Which instructions count the bubble rows. Every path gives the same counts.
//   Portable: one unaligned 64-bit load, mask and popcount per row piece.
//   Avx512:   for runs of voxels along x, one load per row piece serves up to
//             eight voxels, shifted and counted in the lanes of one register;
//             a lone voxel gathers eight of its pieces into one register
//             (AVX-512F + VPOPCNTDQ).
// The default is Avx512 where the CPU (and OS) support it, else Portable. The
// environment variable ROCKBAKE_ALPHA_PATH=portable|avx512 forces a path for
// a run (an unavailable avx512 falls back to portable with a warning).
enum class AlphaPath { Portable, Avx512 };
bool alphaPathAvailable(AlphaPath path);
AlphaPath alphaPath();
// Forces a path for this process (tests, benchmarks); throws std::invalid_argument
// when the CPU lacks it.
void setAlphaPath(AlphaPath path);
const char* alphaPathName(AlphaPath path);

class AirField {
 public:
  // `apron` must be at least the reach of every bubble counted on it.
  AirField(const VoxelRock& rock, int apron);

  void setAir(int x, int y, int z, bool air);
  bool isAir(int x, int y, int z) const;  // any cell within the apron
  int apron() const { return apron_; }

  // Longest piece a bubble row is cut into: a run of voxels up to 7 apart
  // plus the bit phase (up to 7) plus 50 cells fits one 64-bit load.
  static constexpr int kMaxPiece = 50;
  static constexpr int kRunWidth = 8;  // voxels counted together along x

  // A bubble whose rows are cut into pieces and resolved to byte offsets in
  // this field, once for each of the 8 bit phases (x mod 8) of the centre.
  struct BoundBubble {
    std::size_t pieces = 0;
    std::vector<std::int32_t> byte_offset;  // [phase * stride() + i]: from the centre voxel's byte
    std::vector<std::uint64_t> mask;        // [phase * stride() + i]: the piece's bits in that word
    int size = 0;                           // |B|
    double alpha_flat = 0.5;

    // Each phase's table holds `pieces` rounded up to a multiple of 8 (empty masks after `pieces`).
    std::size_t stride() const { return (pieces + 7) / 8 * 8; }
    const std::int32_t* offsets(std::size_t phase) const { return byte_offset.data() + phase * stride(); }
    const std::uint64_t* masks(std::size_t phase) const { return mask.data() + phase * stride(); }
  };
  BoundBubble bind(const Bubble& bubble) const;

  // Number of air cells in v + B for the voxel v = (x, y, z) inside the grid.
  int countAir(const BoundBubble& bubble, int x, int y, int z) const;
  // The same for n <= kRunWidth voxels (x0 + dx[k], y, z) of one row, with
  // 0 = dx[0] < dx[1] < ... < dx[n - 1] < kRunWidth; counts go to out[0..n).
  // Uses alphaPath().
  void countAirRun(const BoundBubble& bubble, int x0, int y, int z, const std::uint8_t* dx, int n, int* out) const;
  // The same on a given path (tests compare the paths).
  void countAirRun(AlphaPath path, const BoundBubble& bubble, int x0, int y, int z, const std::uint8_t* dx, int n,
                   int* out) const;

 private:
  const std::uint64_t* rowWords(int y, int z) const {
    return words_.data() + (std::size_t(z + apron_) * std::size_t(rows_y_) + std::size_t(y + apron_)) * words_per_row_;
  }
  std::uint64_t* rowWords(int y, int z) {
    return words_.data() + (std::size_t(z + apron_) * std::size_t(rows_y_) + std::size_t(y + apron_)) * words_per_row_;
  }

  int apron_ = 0;
  int x_pad_bits_ = 0;  // bits before x = 0 in every row (a multiple of 64 >= apron)
  int rows_y_ = 0;      // ny + 2 apron
  std::size_t words_per_row_ = 0;
  std::vector<std::uint64_t> words_;
};

// The reference: α's numerator by looking up every offset, with the same
// boundary rules. Used by the tests and the benchmark as ground truth.
int naiveCountAir(const VoxelRock& rock, const Bubble& bubble, int x, int y, int z);

// Calibrated exposure s of voxel (x, y, z) for an estimator bound to `field`.
struct BoundEstimator {
  std::vector<AirField::BoundBubble> members;
  std::vector<double> weights;  // sum to 1
};
BoundEstimator bindEstimator(const AirField& field, const BubbleEstimator& estimator);
double exposureAt(const AirField& field, const BoundEstimator& estimator, int x, int y, int z);
// Exposures of a run of voxels (x0 + dx[k], y, z) as for countAirRun; equal to exposureAt's.
void exposureRun(const AirField& field, const BoundEstimator& estimator, int x0, int y, int z, const std::uint8_t* dx,
                 int n, double* s);

}  // namespace rockbake
