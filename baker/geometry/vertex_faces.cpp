#include "geometry/vertex_faces.h"

#include <stdexcept>
#include <string>

namespace rockbake {

VertexFaces::VertexFaces(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::size_t vertex_count)
    : start_(vertex_count + 1, 0) {
  for (const auto& t : triangles)
    for (std::uint32_t v : t) {
      if (v >= vertex_count)
        throw std::out_of_range("VertexFaces: a triangle names vertex " + std::to_string(v) + " of " +
                                std::to_string(vertex_count));
      ++start_[v + 1];
    }
  for (std::size_t v = 0; v < vertex_count; ++v) start_[v + 1] += start_[v];
  faces_.resize(start_[vertex_count]);
  std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
  for (std::uint32_t t = 0; t < triangles.size(); ++t)
    for (std::uint32_t v : triangles[t]) faces_[fill[v]++] = t;
}

}  // namespace rockbake
