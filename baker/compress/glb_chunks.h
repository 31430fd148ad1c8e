// A binary glTF file as its two chunks (glTF 2.0 §4.4): the JSON document and the binary
// buffer. The compressed set (compress/compressed_set.h) reads the full set's GLBs this way
// and patches gltfpack's output, so it links no glTF library: it only moves JSON and bytes.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace rockbake {

struct GlbChunks {
  nlohmann::ordered_json json;
  std::string bin;  // the BIN chunk, empty when the file has none
};

// Throws std::runtime_error naming the file when it cannot be read or is not a GLB.
GlbChunks readGlb(const std::filesystem::path& file);

// The file's bytes: header, the JSON chunk padded with spaces and the BIN chunk with zeros
// to 4 bytes, as §4.4 asks. The JSON is written compactly, keys in the document's order.
std::string glbBytes(const GlbChunks& glb);

}  // namespace rockbake
