// The edges of a mesh's faces, built once and read by every check and repair
// (docs/mesh-kernel.md): for each undirected edge the faces on it in each
// direction; open, non-manifold and misoriented edges; the face across each
// edge where there is exactly one.
//
// Takes triangles (as SurfaceMesh or TriangleMesh hold them, or as a flat
// index buffer, three indices a triangle, as meshoptimizer's) and optionally
// quads. Corner c names a face's c-th vertex and the half-edge from it to the
// face's next vertex: triangle t has corners 3t, 3t + 1, 3t + 2; quad q, after
// all triangles, has corners 3T + 4q … 3T + 4q + 3. Faces are numbered
// triangles first, then quads (face(c)).
//
// Edges are sorted by (a, b), a <= b; each edge's corners are listed forward
// (a → b with a < b) then backward (b → a, and a → a on a face with a
// repeated vertex), each in increasing corner order. Built with a parallel
// sort whose keys are unique, so the table does not depend on the thread
// count. Throws std::length_error beyond 2³² − 2 corners.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace rockbake {

class EdgeTable {
 public:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  struct Edge {
    std::uint32_t a, b;      // vertices, a <= b
    std::uint32_t forward;   // half-edges a → b
    std::uint32_t backward;  // half-edges b → a
    std::uint32_t first;     // where its corners start in the table's corner list

    std::uint32_t faces() const { return forward + backward; }
    // One face each way: what every edge of a closed, consistently oriented 2-manifold is.
    bool paired() const { return forward == 1 && backward == 1; }
    bool boundary() const { return faces() == 1; }                  // a hole's rim
    bool nonManifold() const { return faces() > 2; }                // sheets glued along it
    bool misoriented() const { return faces() == 2 && !paired(); }  // two faces wound the same way
  };

  explicit EdgeTable(const std::vector<std::array<std::uint32_t, 3>>& triangles);
  EdgeTable(const std::vector<std::array<std::uint32_t, 3>>& triangles,
            const std::vector<std::array<std::uint32_t, 4>>& quads);
  explicit EdgeTable(std::span<const std::uint32_t> triangle_indices);

  std::span<const Edge> edges() const { return edges_; }
  const Edge& edge(std::uint32_t e) const { return edges_[e]; }
  // The half-edges a → b and b → a of edge e (corners, increasing).
  std::span<const std::uint32_t> forwardCorners(std::uint32_t e) const {
    return {corners_.data() + edges_[e].first, edges_[e].forward};
  }
  std::span<const std::uint32_t> backwardCorners(std::uint32_t e) const {
    return {corners_.data() + edges_[e].first + edges_[e].forward, edges_[e].backward};
  }
  // The edge between vertices a and b (either order), or kNone.
  std::uint32_t findEdge(std::uint32_t a, std::uint32_t b) const;
  // Edges not paired(): what leaves a mesh not closed, 2-manifold and consistently oriented.
  std::size_t openEdgeCount() const { return open_edges_; }

  std::uint32_t cornerCount() const { return std::uint32_t(twin_.size()); }
  std::uint32_t edgeOf(std::uint32_t c) const { return edge_of_[c]; }
  // The corner across corner c's edge, running the other way, where the edge is
  // paired(); kNone elsewhere. A closed, consistently oriented 2-manifold's
  // half-edge twins.
  std::uint32_t twin(std::uint32_t c) const { return twin_[c]; }
  std::span<const std::uint32_t> twins() const { return twin_; }
  std::uint32_t face(std::uint32_t c) const {
    return c < triangle_corners_ ? c / 3 : triangle_corners_ / 3 + (c - triangle_corners_) / 4;
  }
  // The face across corner c's edge where it is paired(), or kNone.
  std::uint32_t faceAcross(std::uint32_t c) const { return twin_[c] == kNone ? kNone : face(twin_[c]); }
  // The corner after (before) c around its face.
  std::uint32_t next(std::uint32_t c) const {
    if (c < triangle_corners_) return c - c % 3 + (c % 3 + 1) % 3;
    const std::uint32_t k = (c - triangle_corners_) % 4;
    return c - k + (k + 1) % 4;
  }
  std::uint32_t prev(std::uint32_t c) const {
    if (c < triangle_corners_) return c - c % 3 + (c % 3 + 2) % 3;
    const std::uint32_t k = (c - triangle_corners_) % 4;
    return c - k + (k + 3) % 4;
  }

 private:
  template <class Endpoints>
  void build(std::size_t corners, Endpoints&& endpoints);

  std::uint32_t triangle_corners_ = 0;
  std::vector<Edge> edges_;
  std::vector<std::uint32_t> corners_;  // grouped by edge, see Edge::first
  std::vector<std::uint32_t> edge_of_;  // per corner
  std::vector<std::uint32_t> twin_;     // per corner
  std::size_t open_edges_ = 0;
};

}  // namespace rockbake
