#include "geometry/edge_table.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include <tbb/parallel_sort.h>

namespace rockbake {

// Half-edges sorted by (undirected edge, direction, corner): every face on an
// edge side by side. Millions sort in a fraction of the time a hash map of
// lists takes to build.
template <class Endpoints>
void EdgeTable::build(std::size_t corners, Endpoints&& endpoints) {
  if (corners >= kNone) throw std::length_error("EdgeTable: " + std::to_string(corners) + " corners, at most 2^32 - 2");
  const auto count = std::uint32_t(corners);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> half(count);  // (a << 32 | b, backward << 32 | corner)
  for (std::uint32_t c = 0; c < count; ++c) {
    const auto [from, to] = endpoints(c);
    const std::uint64_t a = std::min(from, to), b = std::max(from, to);
    half[c] = {a << 32 | b, std::uint64_t(from < to ? 0 : 1) << 32 | c};
  }
  tbb::parallel_sort(half.begin(), half.end());

  corners_.resize(count);
  edge_of_.resize(count);
  twin_.assign(count, kNone);
  edges_.reserve(count / 2 + 1);
  for (std::uint32_t i = 0; i < count;) {
    const std::uint64_t key = half[i].first;
    Edge e{std::uint32_t(key >> 32), std::uint32_t(key), 0, 0, i};
    const auto edge = std::uint32_t(edges_.size());
    for (; i < count && half[i].first == key; ++i) {
      const auto c = std::uint32_t(half[i].second);
      ++(half[i].second >> 32 ? e.backward : e.forward);
      corners_[i] = c;
      edge_of_[c] = edge;
    }
    if (e.paired()) {
      const std::uint32_t f = corners_[e.first], g = corners_[e.first + 1];
      twin_[f] = g, twin_[g] = f;
    } else {
      ++open_edges_;
    }
    edges_.push_back(e);
  }
}

EdgeTable::EdgeTable(const std::vector<std::array<std::uint32_t, 3>>& triangles) : EdgeTable(triangles, {}) {}

EdgeTable::EdgeTable(const std::vector<std::array<std::uint32_t, 3>>& triangles,
                     const std::vector<std::array<std::uint32_t, 4>>& quads) {
  if (triangles.size() >= kNone / 3) throw std::length_error("EdgeTable: too many triangles");
  triangle_corners_ = std::uint32_t(3 * triangles.size());
  build(std::size_t(triangle_corners_) + 4 * quads.size(), [&](std::uint32_t c) {
    if (c < triangle_corners_) return std::pair{triangles[c / 3][c % 3], triangles[c / 3][(c % 3 + 1) % 3]};
    const auto& q = quads[(c - triangle_corners_) / 4];
    const std::uint32_t k = (c - triangle_corners_) % 4;
    return std::pair{q[k], q[(k + 1) % 4]};
  });
}

EdgeTable::EdgeTable(std::span<const std::uint32_t> triangle_indices) {
  if (triangle_indices.size() % 3 != 0)
    throw std::invalid_argument("EdgeTable: " + std::to_string(triangle_indices.size()) +
                                " triangle indices, not a multiple of 3");
  if (triangle_indices.size() >= kNone) throw std::length_error("EdgeTable: too many triangles");
  triangle_corners_ = std::uint32_t(triangle_indices.size());
  build(triangle_indices.size(), [&](std::uint32_t c) {
    return std::pair{triangle_indices[c], triangle_indices[next(c)]};
  });
}

std::uint32_t EdgeTable::findEdge(std::uint32_t a, std::uint32_t b) const {
  if (a > b) std::swap(a, b);
  const auto it = std::lower_bound(edges_.begin(), edges_.end(), std::pair{a, b}, [](const Edge& e, const auto& key) {
    return e.a < key.first || (e.a == key.first && e.b < key.second);
  });
  return it != edges_.end() && it->a == a && it->b == b ? std::uint32_t(it - edges_.begin()) : kNone;
}

}  // namespace rockbake
