// The check a studio runs on a shipped mesh (docs/meshes.md, What every mesh
// is): every LOD closed, 2-manifold, outward, with no fold-overs and no
// zero-area triangles.
//
// Takes a triangle mesh (quads are ignored) and changes nothing; gives the
// counts and the vertices involved. isDefective is the one test of a bad
// triangle: checkMesh counts what it finds, and the repairs (fold_over_repair.h,
// relax_fold_overs.h, collapsed_specks.h) remove what it finds. Deterministic;
// throws nothing but std::bad_alloc.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/surface_mesh.h"
#include "core/vec3.h"
#include "geometry/edge_table.h"

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

// Triangle t faces against each of the three triangles across its edges
// (negative dot product of the normals normal_of(face) gives). `twins` are an
// EdgeTable's (geometry/edge_table.h), or a repair's copy kept through its flips:
// a triangle with an edge that is not paired is not a fold-over.
template <class NormalOf>
bool foldsOver(std::span<const std::uint32_t> twins, std::uint32_t t, NormalOf&& normal_of) {
  const Vec3d n = normal_of(t);
  for (std::uint32_t k = 0; k < 3; ++k) {
    const std::uint32_t across = twins[3 * t + k];
    if (across == EdgeTable::kNone || !(dot(n, normal_of(across / 3)) < 0)) return false;
  }
  return true;
}

// Triangle t has zero area (geometry/triangle_geometry.h) or folds over.
bool isDefective(const SurfaceMesh& mesh, std::span<const std::uint32_t> twins, std::uint32_t t);

// The piece (triangles connected through shared vertices) of every vertex, as
// DisjointSet::labels numbers them: by each piece's lowest vertex.
std::vector<std::uint32_t> pieceOfVertex(const SurfaceMesh& mesh);

}  // namespace rockbake
