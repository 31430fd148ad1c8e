#include "export/vdb_file.h"

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/TopologyToLevelSet.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <string_view>
#include <utility>

#include "mesh/extract_surfaces.h"
#include "platform/atomic_file.h"
#include "platform/openvdb_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

constexpr int kSdfHalfWidth = 3;  // voxels each side of the surface (OpenVDB's default)
// OpenVDB's archive header is magic (8 bytes), file version (4), library major
// and minor (4 + 4), has-grid-offsets flag (1), then the UUID as 36 characters.
// The tag is searched for within the header rather than assumed at offset 21.
constexpr std::size_t kHeaderSearchBytes = 64;
constexpr std::size_t kUuidLength = 36;

[[noreturn]] void fail(const fs::path& file, const std::string& verb, const std::string& problem) {
  throw std::runtime_error("cannot " + verb + " VDB " + file.string() + ": " + problem);
}

// Dense → sparse. Each 8³ block becomes a leaf in parallel; leaves then join
// the tree serially in block order, so the tree never depends on scheduling.
// activeValue(cell, value&) says whether the voxel is active and sets its value.
template <typename TreeT, typename ActiveValueFn>
typename TreeT::Ptr denseToTree(const GridLayout& layout, typename TreeT::ValueType background,
                                ActiveValueFn activeValue) {
  using LeafT = typename TreeT::LeafNodeType;
  using ValueT = typename TreeT::ValueType;
  constexpr int dim = int(LeafT::DIM);
  const int bx = (layout.nx + dim - 1) / dim;
  const int by = (layout.ny + dim - 1) / dim;
  const int bz = (layout.nz + dim - 1) / dim;
  std::vector<std::unique_ptr<LeafT>> leaves(std::size_t(bx) * std::size_t(by) * std::size_t(bz));

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size()), [&](const auto& blocks) {
    for (std::size_t b = blocks.begin(); b != blocks.end(); ++b) {
      const int x0 = int(b % std::size_t(bx)) * dim;
      const int y0 = int(b / std::size_t(bx) % std::size_t(by)) * dim;
      const int z0 = int(b / (std::size_t(bx) * std::size_t(by))) * dim;
      const int x1 = std::min(x0 + dim, layout.nx);
      const int y1 = std::min(y0 + dim, layout.ny);
      const int z1 = std::min(z0 + dim, layout.nz);
      std::unique_ptr<LeafT> leaf;
      for (int z = z0; z < z1; ++z) {
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) {
            ValueT value = background;
            if (!activeValue(layout.index(x, y, z), value)) continue;
            if (!leaf) leaf = std::make_unique<LeafT>(openvdb::Coord(x0, y0, z0), background, false);
            leaf->setValueOn(LeafT::coordToOffset(openvdb::Coord(x, y, z)), value);
          }
        }
      }
      leaves[b] = std::move(leaf);
    }
  });

  auto tree = std::make_shared<TreeT>(background);
  for (auto& leaf : leaves) {
    if (leaf) tree->addLeaf(leaf.release());
  }
  openvdb::tools::prune(*tree);  // uniform blocks (solid rock) become tiles
  return tree;
}

template <typename GridT>
typename GridT::Ptr namedGrid(typename GridT::TreeType::Ptr tree, const char* name,
                              const openvdb::math::Transform::Ptr& transform) {
  auto grid = GridT::create(tree);
  grid->setName(name);
  grid->setTransform(transform);
  return grid;
}

// FNV-1a, 64 bits, continued from `state`.
std::uint64_t fnv1a(std::uint64_t state, std::string_view bytes) {
  for (unsigned char c : bytes) state = (state ^ c) * 0x100000001b3ull;
  return state;
}

// A UUID-formatted (8-4-4-4-12) stand-in for the archive's random one: 128
// bits from two FNV-1a passes, with different offset bases, over all the
// file's other bytes, marked RFC 9562 version 8 ("custom") so it reads as such.
std::string contentUuid(std::uint64_t high, std::uint64_t low) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string digits(32, '0');
  for (int i = 0; i < 16; ++i) {
    digits[std::size_t(i)] = kHex[(high >> (60 - 4 * i)) & 0xf];
    digits[std::size_t(16 + i)] = kHex[(low >> (60 - 4 * i)) & 0xf];
  }
  digits[12] = '8';                            // version 8
  digits[16] = kHex[8 | ((low >> 60) & 0x3)];  // variant 10xx
  return digits.substr(0, 8) + "-" + digits.substr(8, 4) + "-" + digits.substr(12, 4) + "-" + digits.substr(16, 4) +
         "-" + digits.substr(20, 12);
}

// Passes an archive's bytes through to a file while hashing every byte but
// its UUID's, so the file is written as it is serialized (no copy of it in
// memory) and the content UUID patched in afterwards. The header is held back
// until it is complete, to find the UUID in it.
class ContentHashingBuffer final : public std::streambuf {
 public:
  ContentHashingBuffer(std::ostream& out, const openvdb::io::Archive& archive, const fs::path& file)
      : out_(out), archive_(archive), file_(file) {}

  // Call after the archive is written: the UUID's offset and its stand-in.
  std::pair<std::size_t, std::string> finish() {
    if (at_ == kNotFound) releaseHeader();
    return {at_, contentUuid(high_, low_)};
  }

 protected:
  int_type overflow(int_type ch) override {
    if (traits_type::eq_int_type(ch, traits_type::eof())) return traits_type::not_eof(ch);
    const char c = traits_type::to_char_type(ch);
    return xsputn(&c, 1) == 1 ? ch : traits_type::eof();
  }

  std::streamsize xsputn(const char* data, std::streamsize size) override {
    std::string_view bytes(data, std::size_t(size));
    if (at_ == kNotFound) {
      const std::size_t take = std::min(bytes.size(), kHeaderSearchBytes - header_.size());
      header_.append(bytes.substr(0, take));
      bytes.remove_prefix(take);
      if (header_.size() < kHeaderSearchBytes) return size;
      releaseHeader();
    }
    pass(bytes);
    return out_ ? size : 0;
  }

 private:
  static constexpr std::size_t kNotFound = std::string::npos;

  void releaseHeader() {
    const std::string tag = archive_.getUniqueTag();
    at_ = tag.size() == kUuidLength ? header_.find(tag) : kNotFound;
    if (at_ == kNotFound)
      fail(file_, "write", "OpenVDB archive header has no UUID where expected (library version changed?)");
    const std::string_view header(header_);
    high_ = fnv1a(high_, header.substr(0, at_));
    low_ = fnv1a(low_, header.substr(0, at_));
    out_.write(header_.data(), std::streamsize(at_ + kUuidLength));
    pass(header.substr(at_ + kUuidLength));
  }

  void pass(std::string_view bytes) {
    high_ = fnv1a(high_, bytes);
    low_ = fnv1a(low_, bytes);
    out_.write(bytes.data(), std::streamsize(bytes.size()));
  }

  std::ostream& out_;
  const openvdb::io::Archive& archive_;
  const fs::path& file_;
  std::string header_;
  std::size_t at_ = kNotFound;
  std::uint64_t high_ = 0xcbf29ce484222325ull, low_ = 0x84222325cbf29ce4ull;
};

std::string layoutText(const GridLayout& layout) {
  return std::to_string(layout.nx) + "x" + std::to_string(layout.ny) + "x" + std::to_string(layout.nz);
}

void checkArrays(const VoxelRock& rock, const fs::path& file) {
  const std::size_t cells = rock.layout.cellCount();
  if (rock.material.size() != cells || rock.durability.nx != rock.layout.nx ||
      rock.durability.first.size() != std::size_t(rock.layout.ny) * std::size_t(rock.layout.nz)) {
    fail(file, "write", "the rock's arrays do not match its " + layoutText(rock.layout) + " layout");
  }
}

// Reads grid `name` as a GridT whose transform is the one writeRockVdb gives `layout`.
template <typename GridT>
typename GridT::Ptr readLayoutGrid(openvdb::io::File& vdb, const std::string& name, const GridLayout& layout,
                                   const fs::path& file, const openvdb::Vec3d& pivot) {
  if (!vdb.hasGrid(name)) fail(file, "read", "no grid named \"" + name + "\"");
  auto grid = openvdb::gridPtrCast<GridT>(vdb.readGrid(name));
  if (!grid) fail(file, "read", "grid \"" + name + "\" is not a " + GridT::gridType());

  const auto& transform = grid->constTransform();
  const openvdb::Vec3d first = transform.indexToWorld(openvdb::Coord(0, 0, 0));
  const Vec3d centre = layout.center(0, 0, 0);
  const Vec3d expected{centre[0] - pivot[0], centre[1] - pivot[1], centre[2] - pivot[2]};
  const double tolerance = 1e-6 * layout.h;
  bool same =
      transform.isLinear() && transform.hasUniformScale() && std::abs(transform.voxelSize()[0] - layout.h) <= tolerance;
  for (int axis = 0; axis < 3; ++axis) same = same && std::abs(first[axis] - expected[axis]) <= tolerance;
  if (!same) fail(file, "read", "grid \"" + name + "\" was written for a different grid layout");
  return grid;
}

}  // namespace

namespace {

// The archive of writeRockVdb to `out`; `file` names it in messages.
void writeVdbArchive(const VoxelRock& rock, std::ostream& out, const SmoothedSdf* rock_sdf, const fs::path& file,
                     double sink) {
  initializeOpenVdb();
  checkArrays(rock, file);
  const GridLayout& layout = rock.layout;

  try {
    // Index space stays voxel (x, y, z); world space has the asset's pivot at the origin.
    const std::array<double, 3> pivot = footprintPivot(rock, sink);
    // One transform shared by every grid: Transform::copy() rebuilds the map and
    // recomputes the voxel size from translated corners, which rounds it off h.
    const auto transform = voxelCenterTransform(layout);
    transform->postTranslate(openvdb::Vec3d(-pivot[0], -pivot[1], -pivot[2]));
    auto rockGrid =
        namedGrid<openvdb::BoolGrid>(denseToTree<openvdb::BoolTree>(layout, false,
                                                                    [&](std::size_t cell, bool& value) {
                                                                      value = true;
                                                                      return rock.material[cell] == Material::Rock;
                                                                    }),
                                     "rock", transform);
    auto colluviumGrid =
        namedGrid<openvdb::BoolGrid>(denseToTree<openvdb::BoolTree>(layout, false,
                                                                    [&](std::size_t cell, bool& value) {
                                                                      value = true;
                                                                      return rock.material[cell] == Material::Colluvium;
                                                                    }),
                                     "colluvium", transform);
    // The mesh stage's field is shared with it, so it is written from a shallow copy under our name.
    // Otherwise closingSteps = 0: the sign must follow the occupancy exactly, crevices included.
    openvdb::FloatGrid::Ptr sdfGrid =
        rock_sdf && rock_sdf->grid ? rock_sdf->grid->copy()
                                   : openvdb::tools::topologyToLevelSet(*rockGrid, kSdfHalfWidth, /*closingSteps=*/0);
    sdfGrid->setTransform(transform);
    // Built after the level set, whose working grids are the largest part of
    // writing: the two are never in memory at once.
    auto durabilityGrid =
        namedGrid<openvdb::FloatGrid>(denseToTree<openvdb::FloatTree>(layout, 0.0f,
                                                                      [&](std::size_t cell, float& value) {
                                                                        if (rock.material[cell] != Material::Rock)
                                                                          return false;
                                                                        value = rock.durability[cell];
                                                                        return true;
                                                                      }),
                                      "durability", transform);
    // The history (docs/model.md §14), rock voxels only, where it has a record (background −1; 0 for
    // covered_cycles).
    const auto historyGrid = [&](const RowSpans& spans, const char* name) {
      return namedGrid<openvdb::FloatGrid>(denseToTree<openvdb::FloatTree>(layout, spans.fill,
                                                                           [&](std::size_t cell, float& value) {
                                                                             if (rock.material[cell] != Material::Rock)
                                                                               return false;
                                                                             value = spans[cell];
                                                                             return value != spans.fill;
                                                                           }),
                                           name, transform);
    };
    openvdb::GridPtrVec history;
    if (!rock.history.empty()) {
      history.push_back(historyGrid(rock.history.exposed, "exposed_at"));
      history.push_back(historyGrid(rock.history.covered, "covered_until"));
      history.push_back(historyGrid(rock.history.covered_for, "covered_cycles"));
      history.push_back(historyGrid(rock.history.scarred, "scarred_at"));
    }
    sdfGrid->setName("rock_sdf");
    sdfGrid->setGridClass(openvdb::GRID_LEVEL_SET);
    // Stored as half floats (OpenVDB reads them back as floats): a half keeps each distance
    // within 1/2048 of itself, 1/680 of a voxel three voxels out, and the file is 15 % smaller.
    // The durability and the history stay 32-bit: read exactly, and halves save nothing on them.
    sdfGrid->setSaveFloatAsHalf(true);

    openvdb::MetaMap metadata;
    metadata.insertMeta("creator", openvdb::StringMetadata("rockbake"));
    metadata.insertMeta("voxel_size", openvdb::DoubleMetadata(layout.h));
    metadata.insertMeta("pivot", openvdb::Vec3DMetadata(openvdb::Vec3d(pivot[0], pivot[1], pivot[2])));
#ifdef ROCKBAKE_VERSION
    metadata.insertMeta("rockbake_version", openvdb::StringMetadata(ROCKBAKE_VERSION));
#endif

    openvdb::GridPtrVec grids{rockGrid, colluviumGrid, durabilityGrid, sdfGrid};
    grids.insert(grids.end(), history.begin(), history.end());
    const std::streampos start = out.tellp();
    std::ostream archive_out(nullptr);
    openvdb::io::Stream archive(archive_out);
    ContentHashingBuffer hashing(out, archive, file);
    archive_out.rdbuf(&hashing);
    archive.write(grids, metadata);
    if (!archive_out || !out) fail(file, "write", "serializing the grids failed");
    const auto [at, uuid] = hashing.finish();
    out.seekp(start + std::streamoff(at));
    out.write(uuid.data(), std::streamsize(uuid.size()));
    out.seekp(0, std::ios::end);
    if (!out) fail(file, "write", "patching the archive's UUID failed");
  } catch (const openvdb::Exception& e) {
    fail(file, "write", e.what());
  }
}

}  // namespace

void writeRockVdb(const VoxelRock& rock, const fs::path& file, const SmoothedSdf* rock_sdf, double sink) {
  writeFileAtomically(file, [&](std::ostream& out) { writeVdbArchive(rock, out, rock_sdf, file, sink); });
}

void writeRockVdb(const VoxelRock& rock, std::ostream& out, const SmoothedSdf* rock_sdf) {
  writeVdbArchive(rock, out, rock_sdf, "rock.vdb", 0.0);
}

VoxelRock readRockVdb(const fs::path& file, const GridLayout& layout) {
  initializeOpenVdb();
  VoxelRock rock;
  rock.layout = layout;
  rock.material.assign(layout.cellCount(), Material::Air);

  // Visits every active voxel, tiles expanded, refusing any outside the layout.
  auto forEachActive = [&](const auto& grid, auto&& visit) {
    for (auto it = grid.cbeginValueOn(); it; ++it) {
      const openvdb::CoordBBox box = it.getBoundingBox();
      const openvdb::Coord& lo = box.min();
      const openvdb::Coord& hi = box.max();
      if (!layout.contains(lo.x(), lo.y(), lo.z()) || !layout.contains(hi.x(), hi.y(), hi.z())) {
        fail(file, "read", "grid \"" + grid.getName() + "\" has voxels outside the " + layoutText(layout) + " grid");
      }
      for (int z = lo.z(); z <= hi.z(); ++z) {
        for (int y = lo.y(); y <= hi.y(); ++y) {
          for (int x = lo.x(); x <= hi.x(); ++x) visit(layout.index(x, y, z), *it);
        }
      }
    }
  };

  try {
    std::error_code error;
    if (!fs::exists(file, error)) fail(file, "read", error ? error.message() : "no such file");
    openvdb::io::File vdb(file.string());
    vdb.open(/*delayLoad=*/false);
    // Files written before the pivot have none: their world frame is the grid's.
    openvdb::Vec3d pivot(0.0);
    if (const auto meta = vdb.getMetadata(); meta)
      if (const auto p = meta->getMetadata<openvdb::Vec3DMetadata>("pivot")) pivot = p->value();
    const auto rockGrid = readLayoutGrid<openvdb::BoolGrid>(vdb, "rock", layout, file, pivot);
    const auto colluviumGrid = readLayoutGrid<openvdb::BoolGrid>(vdb, "colluvium", layout, file, pivot);
    const auto durabilityGrid = readLayoutGrid<openvdb::FloatGrid>(vdb, "durability", layout, file, pivot);
    vdb.close();

    forEachActive(*rockGrid, [&](std::size_t cell, bool on) {
      if (on) rock.material[cell] = Material::Rock;
    });
    forEachActive(*colluviumGrid, [&](std::size_t cell, bool on) {
      if (!on) return;
      if (rock.material[cell] == Material::Rock) fail(file, "read", "a voxel is both rock and colluvium");
      rock.material[cell] = Material::Colluvium;
    });
    resetRockValues(rock);  // spans sized to the rock read above
    forEachActive(*durabilityGrid, [&](std::size_t cell, float value) { rock.durability.set(cell, value); });
  } catch (const openvdb::Exception& e) {
    fail(file, "read", e.what());
  }
  return rock;
}

}  // namespace rockbake
