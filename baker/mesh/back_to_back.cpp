#include "mesh/back_to_back.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

#include <tbb/parallel_sort.h>

namespace rockbake {

std::vector<unsigned int> dropBackToBackPairs(std::vector<unsigned int>& indices) {
  const std::size_t n = indices.size() / 3;
  // Triangles by their sorted corners: coincident triangles sit side by side.
  std::vector<std::pair<std::array<unsigned int, 3>, std::size_t>> sorted(n);
  for (std::size_t t = 0; t < n; ++t) {
    std::array<unsigned int, 3> c{indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};
    std::sort(c.begin(), c.end());
    sorted[t] = {c, t};
  }
  tbb::parallel_sort(sorted.begin(), sorted.end());
  std::vector<char> drop(n, 0);
  std::vector<unsigned int> dropped;
  const auto ascending = [&](std::size_t t) {  // winds through its corners in increasing order
    const unsigned int a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
    return (a < b) + (b < c) + (c < a) == 2;
  };
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && sorted[j].first == sorted[i].first) ++j;
    for (std::size_t a = i; a + 1 < j; ++a) {
      const std::size_t ta = sorted[a].second;
      if (drop[ta]) continue;
      for (std::size_t b = a + 1; b < j; ++b) {
        const std::size_t tb = sorted[b].second;
        if (drop[tb] || ascending(ta) == ascending(tb)) continue;
        drop[ta] = drop[tb] = 1;
        dropped.insert(dropped.end(), sorted[i].first.begin(), sorted[i].first.end());
        break;
      }
    }
    i = j;
  }
  if (dropped.empty()) return dropped;
  std::size_t w = 0;
  for (std::size_t t = 0; t < n; ++t)
    if (!drop[t])
      for (int k = 0; k < 3; ++k) indices[w++] = indices[3 * t + k];
  indices.resize(w);
  return dropped;
}

}  // namespace rockbake
