// Reading artists' blockouts (docs/model.md §8): OBJ, PLY (ASCII or binary
// little-endian) and STL (ASCII or binary) into one triangle soup with shared
// vertices. Polygons are fan-triangulated. Coordinates are the file's own.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

// Throws std::runtime_error naming the file and what is wrong with it.
TriangleMesh readTriangleMesh(const std::filesystem::path& file);

}  // namespace rockbake
