// Checks a studio runs on a shipped mesh (docs/meshes.md): every LOD closed,
// 2-manifold, outward, with no fold-overs and no zero-area triangles.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

struct MeshDefects {
  std::size_t open_edges = 0;  // edges not shared by exactly one face in each direction
  std::size_t fold_overs = 0;  // triangles facing against all three edge neighbours
  std::size_t zero_area = 0;   // triangles whose area is below 1e-6 of their longest edge squared
  std::size_t components = 0;  // connected pieces (through shared vertices)
  std::size_t shells = 0;      // of those, the ones enclosing positive volume (not cavities)
  double volume = 0;           // signed, positive when outward
  // The vertices of every open edge, fold-over and zero-area triangle, sorted, once each;
  // and of the open edges alone.
  std::vector<std::uint32_t> defect_vertices, open_edge_vertices;
  bool clean() const { return open_edges == 0 && fold_overs == 0 && zero_area == 0; }
};

// Triangles only (quads are ignored).
MeshDefects checkMesh(const SurfaceMesh& mesh);

// Removes fold-overs and zero-area triangles from a closed, edge-manifold
// triangle mesh by flipping edges: a triangle and its neighbour across an edge
// become the two triangles across the quad's other diagonal, when both new
// triangles have area and face the same side as the quad's surroundings, and
// the new edge does not exist yet. Vertices, attributes and the closed,
// 2-manifold topology are kept; normals are recomputed. Deterministic (the
// triangles are visited in index order). Returns the defects left (0 when clean).
std::size_t repairFoldOvers(SurfaceMesh& mesh);

// What flips and collapses leave, on a mesh with no error bound to keep (a LOD
// simplified to a triangle budget): moves vertices. Each vertex of a fold-over
// or zero-area triangle, in index order, goes to the mean of its neighbours
// (or halfway, or a quarter of the way), or else halfway or a quarter of the
// way towards one neighbour, the first that leaves fewer such triangles
// among those the move can change; up to ten rounds. Topology and attributes
// are kept; normals are recomputed. Deterministic. Returns the defects left.
std::size_t relaxFoldOvers(SurfaceMesh& mesh);

// Removes every connected piece of at most `max_triangles` triangles that holds
// a fold-over or zero-area triangle: at a LOD's budget, a speck of debris
// (a lone colluvium voxel) simplifies to a handful of triangles lying flat on
// each other. The mesh stays closed. Returns the triangles removed.
std::size_t dropCollapsedSpecks(SurfaceMesh& mesh, std::size_t max_triangles);

}  // namespace rockbake
