// The compressed set (docs/delivery.md, "The compressed set"): with the preset's
// delivery.compressed, every LOD's GLB again in OUT/<name>/compressed/, under the same file
// name, made for games and the web:
//   - its maps as KTX2 (Basis Universal, KHR_texture_basisu) embedded in the GLB, one per map
//     the GLB's materials use: the normal map UASTC (RDO, Zstandard, linear), base colour
//     ETC1S (sRGB), ORM ETC1S (linear); each with a full mip chain;
//   - its meshes quantised (KHR_mesh_quantization) and meshopt-compressed
//     (EXT_meshopt_compression) by gltfpack, keeping POSITION, NORMAL, TANGENT, TEXCOORD_0
//     and COLOR_0 (the data attributes COLOR_1 and _DURABILITY, … stay in the full set).
// Node and material names are kept. Every encoder runs single-threaded, many side by side
// (TBB's workers, so --threads bounds them): the files are the same bytes at any thread count.
// The folder is written beside, as .compressed.tmp, and renamed into place complete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compress/compression_tools.h"

namespace rockbake {

inline constexpr const char* kCompressedFolder = "compressed";

// What a set costs (docs/delivery.md, "What a set costs"), every LOD together.
struct SetCost {
  std::uint64_t download_bytes = 0;     // the set's files: GLBs, and the full set's map files they name
  std::uint64_t gpu_texture_bytes = 0;  // each distinct map once, in its GPU format, with a full mip chain
  std::uint64_t gpu_mesh_bytes = 0;     // vertex and index buffers as decoded: every bufferView an accessor reads
  std::uint64_t gpuBytes() const { return gpu_texture_bytes + gpu_mesh_bytes; }
};

struct CompressedSet {
  SetCost full, compressed;
  double seconds = 0;  // wall clock, encoding and packing
};

// Writes <asset_dir>/compressed/ from the full set's `glb_files` (relative to asset_dir, LOD0
// first) and the maps they name; returns both sets' costs. Throws std::runtime_error when a
// tool fails (its own words in the message), leaving no compressed/ folder.
CompressedSet writeCompressedSet(const std::filesystem::path& asset_dir, const std::vector<std::string>& glb_files,
                                 const CompressionTools& tools);

// What one set of GLBs costs, read from the files: `folder` holds the GLBs.
SetCost setCost(const std::filesystem::path& folder, const std::vector<std::string>& glb_files);

// asset.json's "sets": {"full": {...}, "compressed": {"folder", ...}}, each with download_bytes,
// gpu_bytes, gpu_texture_bytes and gpu_mesh_bytes.
nlohmann::ordered_json setsJson(const CompressedSet& set);

}  // namespace rockbake
