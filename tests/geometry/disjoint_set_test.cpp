// The mesh kernel's disjoint sets (geometry/disjoint_set.h; docs/mesh-kernel.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geometry/disjoint_set.h"
#include "core/hash.h"

namespace rockbake {
namespace {

TEST(DisjointSet, UnitesAndReportsWhatItJoined) {
  DisjointSet s(6);
  EXPECT_EQ(s.size(), 6u);
  for (std::uint32_t x = 0; x < 6; ++x) EXPECT_EQ(s.find(x), x);
  EXPECT_TRUE(s.unite(0, 1));
  EXPECT_TRUE(s.unite(2, 3));
  EXPECT_FALSE(s.unite(1, 0));  // one set already
  EXPECT_TRUE(s.connected(0, 1));
  EXPECT_FALSE(s.connected(1, 2));
  EXPECT_TRUE(s.unite(3, 1));
  EXPECT_TRUE(s.connected(0, 2));
  EXPECT_EQ(s.labels(), (std::vector<std::uint32_t>{0, 0, 0, 0, 1, 2}));
}

TEST(DisjointSet, TheHigherRankKeepsItsRootAndTiesKeepTheLowerRoot) {
  DisjointSet s(6);
  s.unite(4, 3);  // a tie: 3 stays the root, of rank 1
  EXPECT_EQ(s.find(4), 3u);
  s.unite(0, 3);  // rank 0 under rank 1
  EXPECT_EQ(s.find(0), 3u);
  s.unite(2, 1);  // a tie: 1 stays the root, of rank 1
  EXPECT_EQ(s.find(2), 1u);
  s.unite(4, 2);  // roots 3 and 1 tie at rank 1: 1, the lower, stays, of rank 2
  EXPECT_EQ(s.find(3), 1u);
  EXPECT_EQ(s.find(0), 1u);
  s.unite(5, 0);  // rank 0 under rank 2
  EXPECT_EQ(s.find(5), 1u);
}

// Labels number the sets by their smallest elements, whatever the order of
// the unions; and they agree with a search over the same links.
TEST(DisjointSet, LabelsDoNotDependOnTheOrderOfTheUnions) {
  constexpr std::uint32_t n = 2000;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> links;
  for (std::uint64_t i = 0; i < 1500; ++i)
    links.push_back({std::uint32_t(mix64(2 * i) % n), std::uint32_t(mix64(2 * i + 1) % n)});
  DisjointSet forward(n), backward(n);
  for (const auto& [a, b] : links) forward.unite(a, b);
  for (auto it = links.rbegin(); it != links.rend(); ++it) backward.unite(it->second, it->first);
  const std::vector<std::uint32_t> labels = forward.labels();
  EXPECT_EQ(backward.labels(), labels);

  // The same components by a depth-first search, numbered by first visit in index order.
  std::vector<std::vector<std::uint32_t>> next(n);
  for (const auto& [a, b] : links) next[a].push_back(b), next[b].push_back(a);
  std::vector<std::uint32_t> expected(n, std::numeric_limits<std::uint32_t>::max());
  std::uint32_t count = 0;
  for (std::uint32_t start = 0; start < n; ++start) {
    if (expected[start] != std::numeric_limits<std::uint32_t>::max()) continue;
    std::vector<std::uint32_t> stack{start};
    expected[start] = count;
    while (!stack.empty()) {
      const std::uint32_t x = stack.back();
      stack.pop_back();
      for (std::uint32_t y : next[x])
        if (expected[y] == std::numeric_limits<std::uint32_t>::max()) expected[y] = count, stack.push_back(y);
    }
    ++count;
  }
  EXPECT_EQ(labels, expected);
  for (std::uint32_t x = 0; x < n; ++x) EXPECT_EQ(forward.connected(x, 0), expected[x] == expected[0]) << x;
}

TEST(DisjointSet, RefusesMoreElementsThanItsIndexHolds) {
  EXPECT_THROW(DisjointSet(std::size_t(std::numeric_limits<std::uint32_t>::max()) + 1), std::length_error);
  EXPECT_EQ(DisjointSet(0).labels().size(), 0u);
}

}  // namespace
}  // namespace rockbake
