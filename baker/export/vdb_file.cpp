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
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/atomic_file.h"
#include "core/openvdb_support.h"
#include "mesh/extract_surfaces.h"

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
void replaceArchiveUuid(std::string& bytes, const std::string& tag, const fs::path& file) {
  const std::string_view header = std::string_view(bytes).substr(0, kHeaderSearchBytes);
  const std::size_t at = tag.size() == kUuidLength ? header.find(tag) : std::string_view::npos;
  if (at == std::string_view::npos) {
    fail(file, "write", "OpenVDB archive header has no UUID where expected (library version changed?)");
  }
  const std::string_view all(bytes);
  const std::string_view before = all.substr(0, at);
  const std::string_view after = all.substr(at + kUuidLength);
  const std::uint64_t high = fnv1a(fnv1a(0xcbf29ce484222325ull, before), after);
  const std::uint64_t low = fnv1a(fnv1a(0x84222325cbf29ce4ull, before), after);

  static constexpr char kHex[] = "0123456789abcdef";
  std::string digits(32, '0');
  for (int i = 0; i < 16; ++i) {
    digits[std::size_t(i)] = kHex[(high >> (60 - 4 * i)) & 0xf];
    digits[std::size_t(16 + i)] = kHex[(low >> (60 - 4 * i)) & 0xf];
  }
  digits[12] = '8';                            // version 8
  digits[16] = kHex[8 | ((low >> 60) & 0x3)];  // variant 10xx
  const std::string uuid = digits.substr(0, 8) + "-" + digits.substr(8, 4) + "-" + digits.substr(12, 4) + "-" +
                           digits.substr(16, 4) + "-" + digits.substr(20, 12);
  bytes.replace(at, kUuidLength, uuid);
}

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

void writeRockVdb(const VoxelRock& rock, const fs::path& file, const SmoothedSdf* rock_sdf) {
  initializeOpenVdb();
  checkArrays(rock, file);
  const GridLayout& layout = rock.layout;

  std::string bytes;
  try {
    // Index space stays voxel (x, y, z); world space has the asset's pivot at the origin.
    const std::array<double, 3> pivot = footprintPivot(rock);
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
    sdfGrid->setName("rock_sdf");
    sdfGrid->setGridClass(openvdb::GRID_LEVEL_SET);

    openvdb::MetaMap metadata;
    metadata.insertMeta("creator", openvdb::StringMetadata("rockbake"));
    metadata.insertMeta("voxel_size", openvdb::DoubleMetadata(layout.h));
    metadata.insertMeta("pivot", openvdb::Vec3DMetadata(openvdb::Vec3d(pivot[0], pivot[1], pivot[2])));
#ifdef ROCKBAKE_VERSION
    metadata.insertMeta("rockbake_version", openvdb::StringMetadata(ROCKBAKE_VERSION));
#endif

    openvdb::GridPtrVec grids{rockGrid, colluviumGrid, durabilityGrid, sdfGrid};
    std::ostringstream buffer(std::ios::out | std::ios::binary);
    openvdb::io::Stream archive(buffer);
    archive.write(grids, metadata);
    if (!buffer) fail(file, "write", "serializing the grids failed");
    bytes = std::move(buffer).str();
    replaceArchiveUuid(bytes, archive.getUniqueTag(), file);
  } catch (const openvdb::Exception& e) {
    fail(file, "write", e.what());
  }
  writeFileAtomically(file, bytes);
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
