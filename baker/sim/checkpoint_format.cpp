#include "sim/checkpoint_format.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "core/error.h"
#include "core/sha256.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;  // the header keeps its keys in order

constexpr char kMagic[8] = {'R', 'B', 'K', 'P', 'O', 'I', 'N', 'T'};
constexpr std::size_t kDigest = 64;
// The header a bake writes nests a few levels (the preset's keyframes); copying
// or printing JSON recurses, so a deeper one is refused while it is parsed.
constexpr int kHeaderDepth = 64;

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

[[noreturn]] void refuse(const fs::path& file, const std::string& problem) {
  throw InputError({file.string()}, "", problem, "use another checkpoint, or bake again");
}

[[noreturn]] void refuseForeign(const fs::path& file) {
  throw InputError({file.string()}, "", "not a rockbake checkpoint",
                   "give a .rbk file written by `rockbake bake --checkpoint-every`");
}

[[noreturn]] void refuseTruncated(const fs::path& file, std::uint64_t size) {
  refuse(file, "the checkpoint is truncated (" + std::to_string(size) + " bytes)");
}

void checkVersion(std::uint32_t version, const fs::path& file) {
  if (version != kCheckpointVersion)
    throw InputError({file.string()}, "",
                     "checkpoint format version " + std::to_string(version) + "; this rockbake reads version " +
                         std::to_string(kCheckpointVersion),
                     "resume it with the rockbake that wrote it, or bake again");
}

// Reads the body after the magic, refusing to go past its end: every count is
// checked against the bytes left before anything is allocated for it.
class Reader {
 public:
  Reader(std::string_view bytes, const fs::path& file) : bytes_(bytes), file_(file) {}
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
    if (count > left() / sizeof(T)) truncated();
    std::vector<T> values(count);
    if (count > 0) std::memcpy(values.data(), bytes_.data() + at_, count * sizeof(T));
    at_ += count * sizeof(T);
    return values;
  }
  // The layout's rows are checked against the bytes left (each row takes at
  // least 8) before RowSpans allocates them.
  RowSpans getSpans(const GridLayout& g) {
    const float fill = get<float>();
    if (std::uint64_t(g.ny) * std::uint64_t(g.nz) > left() / 8) truncated();
    RowSpans spans(g, fill);
    for (std::size_t row = 0; row < spans.values.size(); ++row) {
      spans.first[row] = get<std::int32_t>();
      const auto count = get<std::uint32_t>();
      if (count > std::uint32_t(g.nx) || spans.first[row] < 0 || spans.first[row] + std::int64_t(count) > g.nx)
        refuse(file_, "the checkpoint is corrupt (a row of its spans lies outside its grid)");
      spans.values[row] = getArray<float>(count);
    }
    return spans;
  }
  std::string_view getText(std::uint64_t size) {
    need(size);
    const std::string_view s = bytes_.substr(at_, size);
    at_ += size;
    return s;
  }
  std::size_t left() const { return bytes_.size() - at_; }
  [[noreturn]] void truncated() const {
    refuse(file_, "the checkpoint is truncated or corrupt (its sections run past its end)");
  }

 private:
  void need(std::uint64_t size) {
    if (size > left()) truncated();
  }
  std::string_view bytes_;  // without the checksum
  std::size_t at_ = sizeof(kMagic);
  const fs::path& file_;
};

// The header's values, each checked for its type and range: a checkpoint that
// reads can start a simulation.
class HeaderReader {
 public:
  explicit HeaderReader(const fs::path& file) : file_(file) {}

  json parse(std::string_view text) const {
    const json::parser_callback_t depth = [&](int level, json::parse_event_t, json&) {
      if (level > kHeaderDepth) corrupt(fmt::format("its header nests deeper than {} levels", kHeaderDepth));
      return true;
    };
    return json::parse(text.begin(), text.end(), depth);
  }

  // A whole number in [lo, hi]; `name` is its key path in the header.
  template <typename T>
  T integer(const json& value, std::string_view name, T lo = std::numeric_limits<T>::min(),
            T hi = std::numeric_limits<T>::max()) const {
    const auto within = [&](auto x) { return std::cmp_greater_equal(x, lo) && std::cmp_less_equal(x, hi); };
    if (value.is_number_unsigned() && within(value.get<std::uint64_t>())) return T(value.get<std::uint64_t>());
    if (value.is_number_integer() && !value.is_number_unsigned() && within(value.get<std::int64_t>()))
      return T(value.get<std::int64_t>());
    corrupt(fmt::format("its header's {} is {}, not a whole number from {} to {}", name, shown(value), lo, hi));
  }

  // A finite number, above 0 when `positive`.
  double number(const json& value, std::string_view name, bool positive) const {
    if (!value.is_number() || !std::isfinite(value.get<double>()) || (positive && !(value.get<double>() > 0)))
      corrupt(
          fmt::format("its header's {} is {}, not a finite{} number", name, shown(value), positive ? " positive" : ""));
    return value.get<double>();
  }

  [[noreturn]] void corrupt(const std::string& what) const {
    refuse(file_, "the checkpoint is corrupt (" + what + ")");
  }

 private:
  // A value as messages show it: its JSON, cut short.
  static std::string shown(const json& value) {
    const std::string text = value.dump(-1, ' ', true);  // ASCII: cut anywhere, it stays valid
    return text.size() <= 40 ? text : text.substr(0, 40) + "…";
  }
  const fs::path& file_;
};

// The grid from the header: a real one, whose cells the bytes left can hold
// (a byte of material each), so that nothing sized by it is out of reach.
GridLayout readLayout(const json& l, const HeaderReader& h, std::uint64_t bytes_left) {
  GridLayout g;
  const int most = int(std::clamp<std::uint64_t>(bytes_left, 1, std::numeric_limits<int>::max()));
  g.nx = h.integer<int>(l.at("nx"), "layout.nx", 1, most);
  g.ny = h.integer<int>(l.at("ny"), "layout.ny", 1, most);
  g.nz = h.integer<int>(l.at("nz"), "layout.nz", 1, most);
  const std::uint64_t columns = std::uint64_t(g.nx) * std::uint64_t(g.ny);  // below 2^62: cannot wrap
  if (columns > bytes_left || std::uint64_t(g.nz) > bytes_left / columns)
    h.corrupt(fmt::format("its grid is {}×{}×{}, more cells than its {} bytes hold", g.nx, g.ny, g.nz, bytes_left));
  g.margin = h.integer<int>(l.at("margin"), "layout.margin", 0, std::min({(g.nx - 1) / 2, (g.ny - 1) / 2, g.nz - 1}));
  g.h = h.number(l.at("h"), "layout.h", true);
  const json& origin = l.at("origin");
  if (!origin.is_array() || origin.size() != 3) h.corrupt("its header's layout.origin is not three numbers");
  for (std::size_t i = 0; i < 3; ++i) g.origin[i] = h.number(origin[i], "layout.origin", false);
  g.domain_height = h.number(l.at("domain_height"), "layout.domain_height", true);
  g.ground = l.at("ground").get<bool>();
  return g;
}

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
  const VoxelHistory history = rock.history.empty() ? VoxelHistory(g) : rock.history;
  for (const RowSpans* spans : history.grids()) putSpans(out, *spans);
  put(out, std::uint64_t(rock.rind.size()));  // 0 without a rind, else one byte per cell
  putArray(out, rock.rind);
  put(out, std::uint64_t(c.snapshot.colluvium_columns.size()));
  putArray(out, c.snapshot.colluvium_columns);
  out += sha256Hex(out);
  return out;
}

Checkpoint parseCheckpoint(std::string_view bytes, const fs::path& file) {
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) refuseForeign(file);
  if (bytes.size() < sizeof(kMagic) + 4 + kDigest) refuseTruncated(file, bytes.size());
  const std::string_view body = bytes.substr(0, bytes.size() - kDigest);
  Reader reader(body, file);
  checkVersion(reader.get<std::uint32_t>(), file);
  if (sha256Hex(body) != bytes.substr(body.size()))
    refuse(file, "the checkpoint is truncated or corrupt (its checksum does not match)");

  const HeaderReader h(file);
  try {
    const json header = h.parse(reader.getText(reader.get<std::uint64_t>()));
    Checkpoint c;
    GridLayout& g = c.snapshot.rock.layout;
    g = readLayout(header.at("layout"), h, reader.left());
    const std::uint64_t cells = g.cellCount();
    c.snapshot.cycle = h.integer<int>(header.at("cycle"), "cycle", 0);
    c.snapshot.initial_rock = h.integer<std::size_t>(header.at("initial_rock"), "initial_rock", 0, cells);
    c.preset_file = header.at("preset_file").get<std::string>();
    c.preset_text = header.at("preset_text").get<std::string>();
    const json& o = header.at("overrides");
    c.overrides.sets = o.at("sets").get<std::vector<std::string>>();
    c.overrides.set_origins = o.at("set_origins").get<std::vector<std::string>>();
    if (!o.at("seed").is_null()) c.overrides.seed = h.integer<std::uint64_t>(o.at("seed"), "overrides.seed");
    if (!o.at("resolution").is_null())
      c.overrides.resolution = h.integer<int>(o.at("resolution"), "overrides.resolution");
    c.preset = nlohmann::json::parse(header.at("preset").dump());
    c.preset_hash = header.at("preset_hash").get<std::string>();
    c.cycles = header.at("cycles");
    if (!c.cycles.is_array()) h.corrupt("its header's cycles is not a list");

    if (reader.get<std::uint64_t>() != cells) h.corrupt("its materials are not one per cell of its grid");
    c.snapshot.rock.material = reader.getArray<Material>(cells);
    for (Material m : c.snapshot.rock.material)
      if (m != Material::Air && m != Material::Rock && m != Material::Colluvium)
        h.corrupt(fmt::format("a cell's material is {}", int(m)));
    c.snapshot.rock.integrity = reader.getSpans(g);
    c.snapshot.rock.durability = reader.getSpans(g);
    VoxelHistory& history = c.snapshot.rock.history;
    for (RowSpans* spans : history.grids()) *spans = reader.getSpans(g);
    history.cycles = c.snapshot.cycle;
    const auto rind_cells = reader.get<std::uint64_t>();
    if (rind_cells != 0 && rind_cells != cells) h.corrupt("its rind is neither empty nor one per cell of its grid");
    c.snapshot.rock.rind = reader.getArray<std::uint8_t>(rind_cells);
    const std::uint64_t columns = std::uint64_t(g.nx) * std::uint64_t(g.ny);
    if (reader.get<std::uint64_t>() != columns)
      h.corrupt("its colluvium accumulators are not one per column of its grid");
    c.snapshot.colluvium_columns = reader.getArray<std::int64_t>(columns);
    if (reader.left() != 0) reader.truncated();
    return c;
  } catch (const json::exception& e) {
    refuse(file, std::string("the checkpoint's header is unreadable: ") + e.what());
  }
}

std::uint64_t checkpointHeaderLength(std::string_view prefix, std::uint64_t file_size, const fs::path& file) {
  if (prefix.size() < sizeof(kMagic) || std::memcmp(prefix.data(), kMagic, sizeof(kMagic)) != 0) refuseForeign(file);
  if (file_size < sizeof(kMagic) + 4 + kDigest || prefix.size() < kCheckpointPrefixBytes)
    refuseTruncated(file, file_size);
  Reader reader(prefix, file);
  checkVersion(reader.get<std::uint32_t>(), file);
  const auto length = reader.get<std::uint64_t>();
  if (length > file_size - kCheckpointPrefixBytes - kDigest) reader.truncated();
  return length;
}

std::uint64_t checkpointMostBytes(std::string_view header_text, std::uint64_t file_size, const fs::path& file) {
  const HeaderReader h(file);
  const std::uint64_t before_arrays = kCheckpointPrefixBytes + header_text.size();
  if (file_size < before_arrays + kDigest)
    refuse(file, "the checkpoint is truncated or corrupt (its sections run past its end)");
  try {
    const GridLayout g = readLayout(h.parse(header_text).at("layout"), h, file_size - before_arrays - kDigest);
    const std::uint64_t cells = g.cellCount();  // at most the bytes left: none of the sums below can wrap
    const std::uint64_t rows = std::uint64_t(g.ny) * std::uint64_t(g.nz);
    const std::uint64_t spans = sizeof(float) + rows * 8 + cells * sizeof(float);
    const std::uint64_t columns = std::uint64_t(g.nx) * std::uint64_t(g.ny);
    return before_arrays + 8 + cells + 6 * spans + 8 + cells + 8 + columns * sizeof(std::int64_t) + kDigest;
  } catch (const json::exception& e) {
    refuse(file, std::string("the checkpoint's header is unreadable: ") + e.what());
  }
}

}  // namespace rockbake
