// Disjoint sets over the elements 0 … n − 1 (union-find): which vertices,
// corners, triangles or voxel runs are connected. Union by rank and path
// halving, as Tarjan and van Leeuwen describe them ("Worst-case analysis of
// set union algorithms", JACM 31(2), 1984): near-constant time per operation.
// Ranks are bytes (a rank is at most log2 of the element count): a quarter of
// the memory sizes would take, which the rockfall's millions of voxel runs
// feel.
//
// Deterministic: the representative find() returns depends only on the
// sequence of unite() calls (on a rank tie the lower root stays the root), so
// a caller that unites in a fixed order gets the same representatives on every
// run. labels() numbers the sets by their smallest elements, which does not
// depend on the order of the unions at all. Not thread-safe (find() compresses
// paths). The constructor throws std::length_error beyond 2³² − 1 elements;
// indices are not range-checked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rockbake {

class DisjointSet {
 public:
  explicit DisjointSet(std::size_t count) {
    if (count > std::numeric_limits<std::uint32_t>::max())
      throw std::length_error("DisjointSet: " + std::to_string(count) + " elements, at most 2^32 - 1");
    parent_.resize(count);
    std::iota(parent_.begin(), parent_.end(), 0u);
    rank_.assign(count, 0);
  }

  std::size_t size() const { return parent_.size(); }

  // The representative of x's set.
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }

  // Joins the sets of a and b; false if they were one set already.
  bool unite(std::uint32_t a, std::uint32_t b) {
    std::uint32_t ra = find(a), rb = find(b);
    if (ra == rb) return false;
    if (rank_[ra] < rank_[rb] || (rank_[ra] == rank_[rb] && rb < ra)) std::swap(ra, rb);
    parent_[rb] = ra;
    if (rank_[ra] == rank_[rb]) ++rank_[ra];
    return true;
  }

  bool connected(std::uint32_t a, std::uint32_t b) { return find(a) == find(b); }

  // Each element's set as 0, 1, 2, …, numbered in the order of the sets'
  // smallest elements.
  std::vector<std::uint32_t> labels() {
    constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> label_of_root(parent_.size(), kUnset), labels(parent_.size());
    std::uint32_t next = 0;
    for (std::uint32_t x = 0; x < parent_.size(); ++x) {
      std::uint32_t& label = label_of_root[find(x)];
      if (label == kUnset) label = next++;
      labels[x] = label;
    }
    return labels;
  }

 private:
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint8_t> rank_;  // an upper bound on the height of a root's tree
};

}  // namespace rockbake
