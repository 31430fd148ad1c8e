// Dropping, reordering, merging and copying the vertices of a SurfaceMesh,
// every per-vertex array carried along (docs/mesh-kernel.md): each operation
// here moves every array core/surface_mesh.h lists in kVertexArrays, so an
// array added there is carried by all of them, and by every repair built on
// them, with no change here.
//
// One contract for every operation: each per-vertex array is empty (it stays
// empty) or holds one value per position. Anything else is a programming
// error, caught before anything is changed: std::logic_error naming the mesh
// and the array. A vertex index out of range: std::out_of_range, likewise
// before anything is changed. Deterministic; serial.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "core/surface_mesh.h"

namespace rockbake {

constexpr std::uint32_t kDroppedVertex = std::numeric_limits<std::uint32_t>::max();

// Throws std::logic_error unless every per-vertex array is empty or positions-sized.
void requireVertexArrays(const SurfaceMesh& mesh);

// A mesh of source.size() vertices named as `mesh`, no faces: vertex i holds
// every per-vertex value of mesh's vertex source[i].
SurfaceMesh gatherVertices(const SurfaceMesh& mesh, std::span<const std::uint32_t> source);

// Vertex v becomes vertex new_index[v] (meshoptimizer's remap convention), or
// is dropped where new_index[v] is kDroppedVertex; faces are renumbered (a
// face must not use a dropped vertex). The new indices must cover 0 … k − 1.
// Several vertices mapped to one are welded: the new vertex keeps the values
// of the lowest of them. new_index.size() must be the vertex count.
void remapVertices(SurfaceMesh& mesh, std::span<const std::uint32_t> new_index);

// Drops the vertices no triangle or quad uses, keeping the others' order.
// Returns how many were dropped.
std::size_t compactVertices(SurfaceMesh& mesh);

// Drops the triangles with a repeated vertex (what an edge collapse leaves
// behind), then the vertices no face uses (compactVertices).
void compactMesh(SurfaceMesh& mesh);

// Appends one vertex per entry of `originals`, a copy of every per-vertex
// value of that vertex (splitting a vertex: faces are then pointed at the copy).
void appendVertexCopies(SurfaceMesh& mesh, std::span<const std::uint32_t> originals);

}  // namespace rockbake
