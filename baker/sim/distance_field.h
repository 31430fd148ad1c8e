// Signed distance to the boundary of a set of cells (docs/model.md §4 rind, §8
// variation), world units, negative inside.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/voxel_rock.h"

namespace rockbake {

// A cell's distance is the Euclidean distance from its centre to the nearest
// centre of a cell of the other kind, less half a voxel: the boundary lies
// midway between inside and outside centres, exactly so across a face.
// Cells beyond the grid's sides and top are outside; with the ground each
// cell below z = 0 is what the cell above it is, so the ground adds no
// boundary. Exact (an exact Euclidean transform on the voxels) within `reach`
// of the boundary; beyond it ±reach. Two bytes a cell while the reach is
// within 180 voxels, four beyond; deterministic at any thread count.
class SignedDistanceField {
 public:
  SignedDistanceField(std::vector<std::int16_t> narrow, std::vector<std::int32_t> wide, double h, double reach)
      : narrow_(std::move(narrow)), wide_(std::move(wide)), h_(h), reach_(reach) {}

  // World units, within [-reach, reach].
  double operator[](std::size_t cell) const;

 private:
  // Squared voxel distance to the nearest centre of the other kind, negative
  // inside; only one of the two is filled.
  std::vector<std::int16_t> narrow_;
  std::vector<std::int32_t> wide_;
  double h_, reach_;
};

// `inside`: one flag per cell of `layout`.
SignedDistanceField signedDistance(const std::vector<std::uint8_t>& inside, const GridLayout& layout, double reach);

// Bytes signedDistance holds for a grid of `layout` and `reach` (the field
// and its working buffers), for the memory guard.
std::uint64_t signedDistanceBytes(const GridLayout& layout, double reach);

}  // namespace rockbake
