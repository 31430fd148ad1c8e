#include "compress/compressed_set.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_for_each.h>

#include "compress/glb_chunks.h"
#include "platform/atomic_file.h"
#include "platform/stopwatch.h"

namespace rockbake {
namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

// How a map is encoded, by the material slot that reads it (docs/delivery.md has the measurements).
enum class MapRole { Color, Linear, Normal };

// The flags per role. Each basisu runs single-threaded (-no_multithreading, and -uastc_rdo_m for
// UASTC's RDO pass, whose multithreaded form splits the image by thread count): the bytes are then
// the same on any machine. -mip_clamp matches the GLBs' clamp-to-edge samplers.
std::vector<std::string> basisuArguments(const std::string& basisu, MapRole role, const std::string& in,
                                         const std::string& out) {
  std::vector<std::string> argv{basisu, "-ktx2", "-mipmap", "-mip_clamp", "-no_multithreading"};
  switch (role) {
    case MapRole::Normal:  // UASTC: ETC1S smears a normal map's detail (docs/delivery.md)
      argv.insert(argv.end(), {"-uastc", "-uastc_level", "1", "-uastc_rdo_l", "0.5", "-uastc_rdo_d", "1024",
                               "-uastc_rdo_m", "-ktx2_zstandard_level", "18", "-normal_map", "-linear", "-mip_renorm"});
      break;
    case MapRole::Linear:
      argv.insert(argv.end(), {"-q", "128", "-linear"});
      break;
    case MapRole::Color:
      argv.insert(argv.end(), {"-q", "128"});
      break;
  }
  argv.insert(argv.end(), {"-file", in, "-output_file", out});
  return argv;
}

// The attributes the compressed set keeps (gltfpack 0.18 cannot carry custom ones or a second
// COLOR set, and a game draws with these).
bool keptAttribute(const std::string& name) {
  return name == "POSITION" || name == "NORMAL" || name == "TANGENT" || name == "TEXCOORD_0" || name == "COLOR_0";
}

struct MapJob {
  std::string key;     // the image's uri (relative to the asset folder), or "#" and its bytes' hash when embedded
  std::string source;  // the file basisu reads: in the asset folder, or the work folder's src/
  MapRole role = MapRole::Color;
  std::string ktx2;  // its file in the work folder's ktx2/
  std::uintmax_t bytes = 0;
};

// An image's identity across the GLBs: its uri, or the hash of its bytes when the GLB embeds it (a
// delivery profile may), so that a map every LOD carries (the stones') is encoded once.
std::string imageKey(const GlbChunks& glb, const json& image) {
  if (image.contains("uri")) return image.at("uri").get<std::string>();
  if (!image.contains("bufferView")) return {};
  const json& view = glb.json.at("bufferViews").at(image.at("bufferView").get<std::size_t>());
  const std::string_view bytes(glb.bin.data() + view.value("byteOffset", std::size_t(0)),
                               view.at("byteLength").get<std::size_t>());
  return fmt::format("#{:016x}", std::hash<std::string_view>{}(bytes));
}

std::string_view embeddedBytes(const GlbChunks& glb, const json& image) {
  const json& view = glb.json.at("bufferViews").at(image.at("bufferView").get<std::size_t>());
  return {glb.bin.data() + view.value("byteOffset", std::size_t(0)), view.at("byteLength").get<std::size_t>()};
}

// Every map the GLBs' materials use, once, with the role of the slot that reads it (a normal
// map's role wins over a linear one's, a linear one's over colour's). Embedded maps are written
// to work/src/ for basisu.
std::vector<MapJob> mapJobs(const std::vector<GlbChunks>& glbs, const fs::path& asset_dir, const fs::path& work) {
  std::map<std::string, MapJob> found;
  for (const GlbChunks& glb : glbs) {
    const json& doc = glb.json;
    const auto note = [&](const json& slot, MapRole role) {
      if (!slot.is_object() || !slot.contains("index")) return;
      const json& texture = doc.at("textures").at(slot.at("index").get<std::size_t>());
      if (!texture.contains("source")) return;
      const json& image = doc.at("images").at(texture.at("source").get<std::size_t>());
      const std::string key = imageKey(glb, image);
      if (key.empty()) return;
      auto [at, added] = found.emplace(key, MapJob{key, {}, role, {}, 0});
      at->second.role = std::max(at->second.role, role);
      if (!added) return;
      MapJob& job = at->second;
      if (key[0] == '#') {
        job.source = (work / "src" / (key.substr(1) + ".png")).string();
        writeFileAtomically(job.source, embeddedBytes(glb, image));
        job.ktx2 = key.substr(1) + ".ktx2";
      } else {
        if (key.find("..") != std::string::npos || fs::path(key).is_absolute())
          throw std::runtime_error("the compressed set reads maps inside the asset folder only, not " + key);
        job.source = fs::absolute(asset_dir / key).string();
        job.ktx2 = fs::path(key).stem().string() + ".ktx2";
      }
      job.bytes = fs::file_size(job.source);
    };
    for (const json& m : doc.value("materials", json::array())) {
      const json pbr = m.value("pbrMetallicRoughness", json::object());
      note(pbr.value("baseColorTexture", json()), MapRole::Color);
      note(pbr.value("metallicRoughnessTexture", json()), MapRole::Linear);
      note(m.value("occlusionTexture", json()), MapRole::Linear);
      note(m.value("normalTexture", json()), MapRole::Normal);
    }
  }
  std::vector<MapJob> jobs;
  std::set<std::string> names;
  for (auto& [key, job] : found) {
    if (!names.insert(job.ktx2).second)
      job.ktx2 = fmt::format("{}_{}.ktx2", fs::path(job.ktx2).stem().string(), jobs.size());
    jobs.push_back(job);
  }
  return jobs;
}

// The glTF gltfpack reads: the GLB's JSON with the buffer beside it, each image its KTX2 file,
// and the attributes the set keeps.
void writePackInput(const GlbChunks& glb, const std::vector<MapJob>& jobs, const fs::path& gltf) {
  std::vector<std::string> keys;
  for (const json& image : glb.json.value("images", json::array())) keys.push_back(imageKey(glb, image));
  json doc = glb.json;
  const std::string bin = gltf.stem().string() + ".bin";
  writeFileAtomically(gltf.parent_path() / bin, glb.bin);
  doc.at("buffers").at(0)["uri"] = bin;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    json& image = doc["images"][k];
    const auto job = std::find_if(jobs.begin(), jobs.end(), [&](const MapJob& j) { return j.key == keys[k]; });
    if (job == jobs.end()) continue;  // not a material's map: gltfpack drops what nothing uses
    image.erase("bufferView");        // an embedded map's bytes stay in the buffer, unread
    image["uri"] = "ktx2/" + job->ktx2;
    image["mimeType"] = "image/ktx2";
  }
  for (json& mesh : doc.at("meshes"))
    for (json& primitive : mesh.at("primitives")) {
      json kept = json::object();
      for (const auto& [name, accessor] : primitive.at("attributes").items())
        if (keptAttribute(name)) kept[name] = accessor;
      primitive["attributes"] = kept;
    }
  writeFileAtomically(gltf, doc.dump());
}

// gltfpack 0.18 embeds KTX2 images but names them as a texture's plain source: moved here into
// KHR_texture_basisu, the extension glTF defines for them, and declared.
std::string withBasisuTextures(GlbChunks glb) {
  json& doc = glb.json;
  bool any = false;
  if (!doc.contains("textures")) return glbBytes(glb);
  for (json& texture : doc["textures"]) {
    if (!texture.contains("source")) continue;
    texture["extensions"]["KHR_texture_basisu"]["source"] = texture.at("source");
    texture.erase("source");
    any = true;
  }
  if (any)
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
      json& names = doc[list];
      if (!names.is_array()) names = json::array();
      if (std::find(names.begin(), names.end(), "KHR_texture_basisu") == names.end())
        names.push_back("KHR_texture_basisu");
    }
  return glbBytes(glb);
}

// A folder removed when it goes out of scope (the work folder, a half-made set).
struct RemovedAtEnd {
  fs::path path;
  ~RemovedAtEnd() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

std::uint32_t bigEndian(const unsigned char* p) {
  return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}
std::uint32_t littleEndian(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

// A full mip chain of `w` × `h`, in bytes, at `texel_bytes` a texel (4×4 blocks of `block_bytes`
// when block_bytes > 0).
std::uint64_t mipChainBytes(std::uint64_t w, std::uint64_t h, std::uint64_t levels, double texel_bytes,
                            std::uint64_t block_bytes) {
  std::uint64_t total = 0;
  for (std::uint64_t l = 0; l < levels; ++l) {
    const std::uint64_t lw = std::max<std::uint64_t>(1, w >> l), lh = std::max<std::uint64_t>(1, h >> l);
    total += block_bytes ? ((lw + 3) / 4) * ((lh + 3) / 4) * block_bytes : std::uint64_t(lw * lh * texel_bytes);
  }
  return total;
}

std::uint64_t fullChainLevels(std::uint64_t w, std::uint64_t h) {
  std::uint64_t levels = 1;
  for (std::uint64_t s = std::max(w, h); s > 1; s >>= 1) ++levels;
  return levels;
}

// A PNG as a GPU holds it uncompressed: RGBA8 a texel (RGBA16 for a 16-bit PNG), full mip chain.
std::uint64_t pngGpuBytes(const std::string& bytes, const std::string& what) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 29 || std::memcmp(p, "\x89PNG\r\n\x1a\n", 8) != 0 || std::memcmp(p + 12, "IHDR", 4) != 0)
    throw std::runtime_error(what + " is not a PNG");
  const std::uint64_t w = bigEndian(p + 16), h = bigEndian(p + 20), depth = p[24];
  return mipChainBytes(w, h, fullChainLevels(w, h), depth == 16 ? 8.0 : 4.0, 0);
}

// A KTX2 of Basis Universal data as a GPU holds it once transcoded: UASTC to BC7 / ASTC 4×4,
// 16 bytes a 4×4 block; ETC1S to BC1 / ETC1 (8 bytes a block) without alpha, BC3 / ETC2 RGBA
// (16) with it; its own levels.
std::uint64_t ktx2GpuBytes(std::string_view bytes, const std::string& what) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  static constexpr unsigned char kId[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < 80 || std::memcmp(p, kId, 12) != 0) throw std::runtime_error(what + " is not a KTX2");
  const std::uint64_t w = littleEndian(p + 20), h = std::max<std::uint32_t>(1, littleEndian(p + 24));
  const std::uint64_t levels = std::max<std::uint32_t>(1, littleEndian(p + 40));
  const std::size_t dfd = littleEndian(p + 48);
  if (dfd + 28 > bytes.size()) throw std::runtime_error(what + ": its data format descriptor is cut short");
  const unsigned colour_model = p[dfd + 12];
  const std::size_t samples = ((p[dfd + 10] | p[dfd + 11] << 8) - 24) / 16;
  std::uint64_t block = 16;                               // UASTC (166), or anything else taken at its widest
  if (colour_model == 163) block = samples > 1 ? 16 : 8;  // ETC1S
  return mipChainBytes(w, h, levels, 0, block);
}

std::string readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

// The vertex and index buffers a GLB's accessors read, as decoded (a meshopt bufferView's
// byteLength is its decoded size).
std::uint64_t meshBytes(const json& doc) {
  std::set<std::size_t> views;
  for (const json& a : doc.value("accessors", json::array()))
    if (a.contains("bufferView")) views.insert(a.at("bufferView").get<std::size_t>());
  std::uint64_t total = 0;
  for (std::size_t v : views) total += doc.at("bufferViews").at(v).at("byteLength").get<std::uint64_t>();
  return total;
}

}  // namespace

SetCost setCost(const fs::path& folder, const std::vector<std::string>& glb_files) {
  SetCost cost;
  std::set<std::string> files;     // the full set's map files, each once
  std::set<std::string> embedded;  // the compressed set's images, each distinct one once
  for (const std::string& file : glb_files) {
    const GlbChunks glb = readGlb(folder / file);
    cost.download_bytes += fs::file_size(folder / file);
    cost.gpu_mesh_bytes += meshBytes(glb.json);
    for (const json& image : glb.json.value("images", json::array())) {
      if (image.contains("uri")) {
        const std::string uri = image.at("uri");
        if (!files.insert(uri).second) continue;
        const std::string bytes = readBytes(folder / uri);
        cost.download_bytes += bytes.size();
        cost.gpu_texture_bytes += pngGpuBytes(bytes, (folder / uri).string());
      } else if (image.contains("bufferView")) {
        const json& view = glb.json.at("bufferViews").at(image.at("bufferView").get<std::size_t>());
        const std::string bytes =
            glb.bin.substr(view.value("byteOffset", std::size_t(0)), view.at("byteLength").get<std::size_t>());
        if (!embedded.insert(bytes).second) continue;
        const std::string what = (folder / file).string() + "'s image";
        cost.gpu_texture_bytes += bytes.rfind("\x89PNG", 0) == 0 ? pngGpuBytes(bytes, what) : ktx2GpuBytes(bytes, what);
      }
    }
  }
  return cost;
}

CompressedSet writeCompressedSet(const fs::path& asset_dir, const std::vector<std::string>& glb_files,
                                 const CompressionTools& tools) {
  const Stopwatch clock;
  RemovedAtEnd work{asset_dir / ".compress-work"}, staged{asset_dir / ".compressed.tmp"};
  fs::remove_all(work.path);
  fs::remove_all(staged.path);
  fs::create_directories(work.path / "ktx2");
  fs::create_directories(work.path / "logs");
  fs::create_directories(staged.path);

  std::vector<GlbChunks> glbs;
  for (const std::string& file : glb_files) glbs.push_back(readGlb(asset_dir / file));
  fs::create_directories(work.path / "src");
  std::vector<MapJob> jobs = mapJobs(glbs, asset_dir, work.path);
  // Largest first, so the long encodes start at once and the small ones fill in beside them.
  std::vector<const MapJob*> order;
  for (const MapJob& j : jobs) order.push_back(&j);
  std::stable_sort(order.begin(), order.end(), [](const MapJob* a, const MapJob* b) {
    return (a->role == MapRole::Normal ? 4 : 1) * a->bytes > (b->role == MapRole::Normal ? 4 : 1) * b->bytes;
  });
  tbb::parallel_for_each(order.begin(), order.end(), [&](const MapJob* job) {
    runTool(basisuArguments(tools.basisu, job->role, job->source, "ktx2/" + job->ktx2), work.path,
            work.path / "logs" / (job->ktx2 + ".log"));
  });
  const double encode_seconds = clock.elapsed();

  tbb::parallel_for(std::size_t(0), glb_files.size(), [&](std::size_t i) {
    const std::string stem = fmt::format("lod{}", i);
    writePackInput(glbs[i], jobs, work.path / (stem + ".gltf"));
    // -c: meshopt compression with quantised attributes; -kn -km: node and material names kept.
    runTool({tools.gltfpack, "-i", stem + ".gltf", "-o", stem + ".glb", "-c", "-kn", "-km"}, work.path,
            work.path / "logs" / (stem + ".gltfpack.log"));
    writeFileAtomically(staged.path / glb_files[i], withBasisuTextures(readGlb(work.path / (stem + ".glb"))));
  });

  CompressedSet set;
  set.full = setCost(asset_dir, glb_files);
  set.compressed = setCost(staged.path, glb_files);
  const fs::path folder = asset_dir / kCompressedFolder;
  fs::remove_all(folder);
  fs::rename(staged.path, folder);
  set.seconds = clock.elapsed();
  spdlog::debug("compressed set: {} maps encoded in {:.1f} s, {} GLBs packed in {:.1f} s", jobs.size(), encode_seconds,
                glb_files.size(), set.seconds - encode_seconds);
  return set;
}

json setsJson(const CompressedSet& set) {
  const auto cost = [](const SetCost& c) {
    return json{{"download_bytes", c.download_bytes},
                {"gpu_bytes", c.gpuBytes()},
                {"gpu_texture_bytes", c.gpu_texture_bytes},
                {"gpu_mesh_bytes", c.gpu_mesh_bytes}};
  };
  json compressed = {{"folder", kCompressedFolder}};
  compressed.update(cost(set.compressed));
  return {{"full", cost(set.full)}, {"compressed", compressed}};
}

}  // namespace rockbake
