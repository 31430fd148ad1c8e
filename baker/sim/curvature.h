// Exact bubble counts α and calibrated exposure s (SPEC §2.3).
//
// AirField keeps one bit per cell (1 = air) in rows along x, with an apron of
// cells around the grid whose bits follow SPEC §2.3: air beyond the sides and
// the top, solid below the ground (air when grid.ground is false). Colluvium
// counts as solid. Counting a bubble is then one masked popcount per bubble
// row instead of one lookup per offset: O(R²) per voxel, not O(R³), and it
// equals the naive loop exactly.
#pragma once

#include <cstdint>
#include <vector>

#include "core/voxel_rock.h"
#include "sim/bubble.h"

namespace rockbake {

class AirField {
 public:
  // `apron` must be at least the reach of every bubble counted on it.
  AirField(const VoxelRock& rock, int apron);

  void setAir(int x, int y, int z, bool air);
  bool isAir(int x, int y, int z) const;  // any cell within the apron
  int apron() const { return apron_; }

  // A bubble whose rows are resolved to word offsets in this field.
  struct BoundBubble {
    struct Row {
      std::ptrdiff_t word_offset;  // from the centre cell's row
      int x_min, x_max;
      std::uint64_t mask;  // x_max - x_min + 1 low bits (rows of up to 57 cells)
    };
    std::vector<Row> rows;
    int size = 0;            // |B|
    bool short_rows = true;  // every row fits one unaligned 64-bit load
    double alpha_flat = 0.5;
  };
  BoundBubble bind(const Bubble& bubble) const;

  // Number of air cells in v + B for the voxel v = (x, y, z) inside the grid.
  int countAir(const BoundBubble& bubble, int x, int y, int z) const;

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

}  // namespace rockbake
