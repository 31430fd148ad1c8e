#include "pipeline/checkpoint.h"

#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/sha256.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;  // the header keeps its keys in order

constexpr char kMagic[8] = {'R', 'B', 'K', 'P', 'O', 'I', 'N', 'T'};
constexpr std::size_t kDigest = 64;

template <typename T>
void put(std::string& out, const T& value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

template <typename T>
void putArray(std::string& out, const std::vector<T>& values) {
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// Row spans (core/voxel_rock.h) as they are: fill, then per row its first x,
// its length and its values, so a restored simulation holds the same spans.
void putSpans(std::string& out, const RowSpans& spans) {
  put(out, spans.fill);
  for (std::size_t row = 0; row < spans.values.size(); ++row) {
    put(out, spans.first[row]);
    put(out, std::uint32_t(spans.values[row].size()));
    putArray(out, spans.values[row]);
  }
}

// Reads the body after the magic, refusing to go past its end.
class Reader {
 public:
  Reader(std::string_view bytes, std::size_t end, const fs::path& file) : bytes_(bytes), end_(end), file_(file) {}
  template <typename T>
  T get() {
    T value;
    need(sizeof(T));
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  template <typename T>
  std::vector<T> getArray(std::uint64_t count) {
    if (count > (end_ - at_) / sizeof(T)) truncated();
    std::vector<T> values(count);
    std::memcpy(values.data(), bytes_.data() + at_, count * sizeof(T));
    at_ += count * sizeof(T);
    return values;
  }
  RowSpans getSpans(const GridLayout& g) {
    RowSpans spans(g, get<float>());
    for (std::size_t row = 0; row < spans.values.size(); ++row) {
      spans.first[row] = get<std::int32_t>();
      const auto count = get<std::uint32_t>();
      if (count > std::uint32_t(g.nx) || spans.first[row] < 0 || spans.first[row] + std::int64_t(count) > g.nx)
        truncated();
      spans.values[row] = getArray<float>(count);
    }
    return spans;
  }
  std::string getString(std::uint64_t size) {
    need(size);
    std::string s(bytes_.substr(at_, size));
    at_ += size;
    return s;
  }
  std::size_t at() const { return at_; }
  [[noreturn]] void truncated() const {
    throw InputError({file_.string()}, "", "the checkpoint is truncated or corrupt (its sections run past its end)",
                     "use another checkpoint, or bake again");
  }

 private:
  void need(std::uint64_t size) {
    if (size > end_ - at_) truncated();
  }
  std::string_view bytes_;
  std::size_t end_;
  std::size_t at_ = sizeof(kMagic);
  const fs::path& file_;
};

}  // namespace

std::string checkpointFileName(double time) {
  return fmt::format("{:.6g}.rbk", time);
}

std::string checkpointBytes(const Checkpoint& c) {
  const VoxelRock& rock = c.snapshot.rock;
  const GridLayout& g = rock.layout;
  const json header = {{"layout",
                        {{"nx", g.nx},
                         {"ny", g.ny},
                         {"nz", g.nz},
                         {"margin", g.margin},
                         {"h", g.h},
                         {"origin", g.origin},
                         {"domain_height", g.domain_height},
                         {"ground", g.ground}}},
                       {"cycle", c.snapshot.cycle},
                       {"time", c.snapshot.cycle * g.h},
                       {"initial_rock", c.snapshot.initial_rock},
                       {"preset_file", c.preset_file.string()},
                       {"preset_text", c.preset_text},
                       {"overrides",
                        {{"sets", c.overrides.sets},
                         {"set_origins", c.overrides.set_origins},
                         {"seed", c.overrides.seed ? json(*c.overrides.seed) : json(nullptr)},
                         {"resolution", c.overrides.resolution ? json(*c.overrides.resolution) : json(nullptr)}}},
                       {"preset", json::parse(c.preset.dump())},
                       {"preset_hash", c.preset_hash},
                       {"cycles", c.cycles}};
  std::string out(kMagic, sizeof(kMagic));
  put(out, kCheckpointVersion);
  const std::string header_text = header.dump();
  put(out, std::uint64_t(header_text.size()));
  out += header_text;
  put(out, std::uint64_t(g.cellCount()));
  static_assert(sizeof(Material) == 1);
  putArray(out, rock.material);
  putSpans(out, rock.integrity);
  putSpans(out, rock.durability);
  put(out, std::uint64_t(rock.rind.size()));  // 0 without a rind, else one byte per cell
  putArray(out, rock.rind);
  put(out, std::uint64_t(c.snapshot.colluvium_columns.size()));
  putArray(out, c.snapshot.colluvium_columns);
  out += sha256Hex(out);
  return out;
}

void writeCheckpoint(const fs::path& file, const Checkpoint& c) {
  writeFileAtomically(file, checkpointBytes(c));
}

Checkpoint parseCheckpoint(std::string_view bytes, const fs::path& file) {
  const auto bad = [&](const std::string& problem, const std::string& hint) {
    throw InputError({file.string()}, "", problem, hint);
  };
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    bad("not a rockbake checkpoint", "give a .rbk file written by `rockbake bake --checkpoint-every`");
  if (bytes.size() < sizeof(kMagic) + 4 + kDigest)
    bad("the checkpoint is truncated (" + std::to_string(bytes.size()) + " bytes)",
        "use another checkpoint, or bake again");
  Reader reader(bytes, bytes.size() - kDigest, file);
  const auto version = reader.get<std::uint32_t>();
  if (version != kCheckpointVersion)
    bad("checkpoint format version " + std::to_string(version) + "; this rockbake reads version " +
            std::to_string(kCheckpointVersion),
        "resume it with the rockbake that wrote it, or bake again");
  if (sha256Hex(bytes.substr(0, bytes.size() - kDigest)) != bytes.substr(bytes.size() - kDigest))
    bad("the checkpoint is truncated or corrupt (its checksum does not match)",
        "use another checkpoint, or bake again");

  json header;
  try {
    header = json::parse(reader.getString(reader.get<std::uint64_t>()));
    Checkpoint c;
    GridLayout& g = c.snapshot.rock.layout;
    const json& l = header.at("layout");
    g.nx = l.at("nx"), g.ny = l.at("ny"), g.nz = l.at("nz"), g.margin = l.at("margin");
    g.h = l.at("h"), g.origin = l.at("origin"), g.domain_height = l.at("domain_height"), g.ground = l.at("ground");
    c.snapshot.cycle = header.at("cycle");
    c.snapshot.initial_rock = header.at("initial_rock");
    c.preset_file = header.at("preset_file").get<std::string>();
    c.preset_text = header.at("preset_text");
    const json& o = header.at("overrides");
    c.overrides.sets = o.at("sets").get<std::vector<std::string>>();
    c.overrides.set_origins = o.at("set_origins").get<std::vector<std::string>>();
    if (!o.at("seed").is_null()) c.overrides.seed = o.at("seed").get<std::uint64_t>();
    if (!o.at("resolution").is_null()) c.overrides.resolution = o.at("resolution").get<int>();
    c.preset = nlohmann::json::parse(header.at("preset").dump());
    c.preset_hash = header.at("preset_hash");
    c.cycles = header.at("cycles");
    const auto cells = reader.get<std::uint64_t>();
    if (cells != g.cellCount()) reader.truncated();
    c.snapshot.rock.material = reader.getArray<Material>(cells);
    c.snapshot.rock.integrity = reader.getSpans(g);
    c.snapshot.rock.durability = reader.getSpans(g);
    const auto rind_cells = reader.get<std::uint64_t>();
    if (rind_cells != 0 && rind_cells != cells) reader.truncated();
    c.snapshot.rock.rind = reader.getArray<std::uint8_t>(rind_cells);
    c.snapshot.colluvium_columns = reader.getArray<std::int64_t>(reader.get<std::uint64_t>());
    if (reader.at() != bytes.size() - kDigest) reader.truncated();
    for (Material m : c.snapshot.rock.material)
      if (m != Material::Air && m != Material::Rock && m != Material::Colluvium) reader.truncated();
    return c;
  } catch (const json::exception& e) {
    bad(std::string("the checkpoint's header is unreadable: ") + e.what(), "use another checkpoint, or bake again");
  }
  return {};
}

Checkpoint readCheckpoint(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError({file.string()}, "", "cannot be read",
                     "check the path (checkpoints are OUT/<name>/checkpoints/<time>.rbk)");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parseCheckpoint(buffer.str(), file);
}

}  // namespace rockbake
