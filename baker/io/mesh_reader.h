// Reading artists' blockouts (SPEC §2.8): OBJ, PLY (ASCII or binary
// little-endian) and STL (ASCII or binary) into one triangle soup with shared
// vertices. Polygons are fan-triangulated. Coordinates are the file's own.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace rockbake {

struct TriangleMesh {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// Throws std::runtime_error naming the file and what is wrong with it.
TriangleMesh readTriangleMesh(const std::filesystem::path& file);

// Edges of the mesh not shared by exactly two triangles of opposite
// orientation: empty for a closed, consistently oriented 2-manifold.
struct OpenEdge {
  std::uint32_t a, b;
  int uses;  // how many triangles use the edge (either direction)
};
std::vector<OpenEdge> findOpenEdges(const TriangleMesh& mesh);

// Signed volume (positive when the triangles face outwards).
double signedVolume(const TriangleMesh& mesh);

}  // namespace rockbake
