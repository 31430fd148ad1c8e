#include "compress/glb_chunks.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rockbake {
namespace {

constexpr std::uint32_t kMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

std::uint32_t word(const std::string& bytes, std::size_t at) {
  std::uint32_t w = 0;
  std::memcpy(&w, bytes.data() + at, 4);  // little-endian, as the hosts rockbake builds for
  return w;
}

void putWord(std::string& bytes, std::uint32_t w) {
  bytes.append(reinterpret_cast<const char*>(&w), 4);
}

}  // namespace

GlbChunks readGlb(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::ostringstream all;
  all << in.rdbuf();
  const std::string bytes = all.str();
  if (bytes.size() < 20 || word(bytes, 0) != kMagic || word(bytes, 4) != 2)
    throw std::runtime_error(file.string() + " is not a glTF 2.0 binary");
  GlbChunks glb;
  bool have_json = false;
  for (std::size_t at = 12; at + 8 <= bytes.size();) {
    const std::size_t size = word(bytes, at), kind = word(bytes, at + 4);
    if (at + 8 + size > bytes.size()) throw std::runtime_error(file.string() + ": a chunk runs past the file's end");
    const std::string chunk = bytes.substr(at + 8, size);
    if (kind == kJsonChunk) {
      glb.json = nlohmann::ordered_json::parse(chunk);
      have_json = true;
    } else if (kind == kBinChunk) {
      glb.bin = chunk;
    }
    at += 8 + size;
  }
  if (!have_json) throw std::runtime_error(file.string() + " has no JSON chunk");
  return glb;
}

std::string glbBytes(const GlbChunks& glb) {
  std::string text = glb.json.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  std::string bin = glb.bin;
  bin.append((4 - bin.size() % 4) % 4, '\0');
  std::string out;
  putWord(out, kMagic);
  putWord(out, 2);
  putWord(out, std::uint32_t(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
  putWord(out, std::uint32_t(text.size()));
  putWord(out, kJsonChunk);
  out += text;
  if (!bin.empty()) {
    putWord(out, std::uint32_t(bin.size()));
    putWord(out, kBinChunk);
    out += bin;
  }
  return out;
}

}  // namespace rockbake
