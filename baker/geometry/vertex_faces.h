// The triangles around each vertex (docs/mesh-kernel.md): for vertex v, every
// triangle with v as a corner, in increasing triangle order (a triangle with v
// at two corners is listed twice). Built once, in two passes over the
// triangles (counts, then fill), and read by the repairs that move or
// collapse vertices. A snapshot: it does not follow later changes to the
// triangles. Throws std::out_of_range if a triangle names a vertex at or past
// `vertex_count`.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rockbake {

class VertexFaces {
 public:
  VertexFaces(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::size_t vertex_count);

  std::span<const std::uint32_t> operator[](std::uint32_t v) const {
    return {faces_.data() + start_[v], start_[v + 1] - start_[v]};
  }
  std::size_t vertexCount() const { return start_.size() - 1; }

 private:
  std::vector<std::size_t> start_;  // vertex v's triangles are faces_[start_[v], start_[v + 1])
  std::vector<std::uint32_t> faces_;
};

}  // namespace rockbake
