// File I/O: atomic replacement, PNG reading, the rock.vdb export (docs/model.md §8, docs/formats.md).
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <png.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "platform/atomic_file.h"
#include "platform/png_image.h"
#include "export/vdb_file.h"
#include "mesh/extract_surfaces.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using test::readBytes;
using test::TempDir;
using test::writeText;

std::vector<std::string> folderEntries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Runs `f`, expecting std::runtime_error whose message contains `needle`.
template <typename F>
void expectRuntimeErrorMentioning(F&& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning " << needle;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------- atomic files

TEST(AtomicFile, ReplacesContentAndLeavesNoTemporary) {
  TempDir dir;
  const fs::path target = dir.path() / "rock.vdb";
  writeFileAtomically(target, std::string_view("first version, longer than the second"));
  EXPECT_EQ(readBytes(target), "first version, longer than the second");
  writeFileAtomically(target, std::string_view("second"));
  EXPECT_EQ(readBytes(target), "second");
  EXPECT_EQ(folderEntries(dir.path()), std::vector<std::string>{"rock.vdb"});
}

TEST(AtomicFile, StreamsLargeContentAndCreatesParentFolders) {
  TempDir dir;
  const fs::path target = dir.path() / "out" / "small" / "stats.json";
  std::string expected;
  for (int i = 0; i < 200000; ++i) expected += std::to_string(i) + ",";
  writeFileAtomically(target, [&](std::ostream& out) {
    for (int i = 0; i < 200000; ++i) out << i << ',';
  });
  EXPECT_EQ(readBytes(target), expected);
  EXPECT_EQ(folderEntries(target.parent_path()), std::vector<std::string>{"stats.json"});
}

TEST(AtomicFile, FolderThatIsAFileThrowsAndLeavesNothing) {
  TempDir dir;
  writeText(dir.path() / "blocker", "a file, not a folder");
  const fs::path target = dir.path() / "blocker" / "rock.vdb";
  expectRuntimeErrorMentioning([&] { writeFileAtomically(target, std::string_view("x")); }, target.string());
  EXPECT_EQ(folderEntries(dir.path()), std::vector<std::string>{"blocker"});
  EXPECT_EQ(readBytes(dir.path() / "blocker"), "a file, not a folder");
}

TEST(AtomicFile, FailedRenameRemovesTheTemporary) {
  TempDir dir;
  const fs::path target = dir.path() / "taken";
  fs::create_directory(target);  // a non-empty folder cannot be renamed over
  writeText(target / "inside", "keep");
  expectRuntimeErrorMentioning([&] { writeFileAtomically(target, std::string_view("x")); }, target.string());
  EXPECT_EQ(folderEntries(dir.path()), std::vector<std::string>{"taken"});
}

TEST(AtomicFile, WriterExceptionPropagatesAndKeepsTheOldFile) {
  TempDir dir;
  const fs::path target = dir.path() / "manifest.json";
  writeFileAtomically(target, std::string_view("old"));
  struct WriterFailed {};
  EXPECT_THROW(writeFileAtomically(target,
                                   [](std::ostream& out) {
                                     out << "half of the new";
                                     throw WriterFailed{};
                                   }),
               WriterFailed);
  EXPECT_EQ(readBytes(target), "old");
  EXPECT_EQ(folderEntries(dir.path()), std::vector<std::string>{"manifest.json"});
}

// ---------------------------------------------------------------- PNG

// A PNG written with libpng's full API, so any colour type and bit depth can
// be produced. `rows` holds packed rows exactly as they go into the file.
struct PngSpec {
  int width = 0, height = 0;
  int color_type = PNG_COLOR_TYPE_GRAY;
  int bit_depth = 8;
  std::vector<png_byte> rows{};
  std::vector<png_color> palette{};
  std::vector<png_byte> palette_alpha{};  // tRNS for palette images
};

void writePng(const fs::path& file, const PngSpec& spec) {
  std::FILE* out = std::fopen(file.c_str(), "wb");
  if (!out) throw std::runtime_error("cannot create " + file.string());
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(out);
    throw std::runtime_error("libpng failed writing " + file.string());
  }
  png_init_io(png, out);
  png_set_IHDR(png, info, png_uint_32(spec.width), png_uint_32(spec.height), spec.bit_depth, spec.color_type,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (!spec.palette.empty()) png_set_PLTE(png, info, spec.palette.data(), int(spec.palette.size()));
  if (!spec.palette_alpha.empty()) {
    png_set_tRNS(png, info, spec.palette_alpha.data(), int(spec.palette_alpha.size()), nullptr);
  }
  png_write_info(png, info);
  const std::size_t row_bytes = png_get_rowbytes(png, info);
  if (spec.rows.size() != row_bytes * std::size_t(spec.height)) png_error(png, "test rows: wrong size");
  for (int y = 0; y < spec.height; ++y) png_write_row(png, spec.rows.data() + std::size_t(y) * row_bytes);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(out);
}

TEST(PngImage, GreyIsReadRowMajorTopRowFirst) {
  TempDir dir;
  const fs::path file = dir.path() / "grey.png";
  writePng(file, {.width = 3, .height = 2, .rows = {0, 128, 255, 10, 20, 30}});
  const GrayImage image = readPngGray(file);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  EXPECT_EQ(image.pixels, (std::vector<std::uint8_t>{0, 128, 255, 10, 20, 30}));
  EXPECT_EQ(image.at(2, 0), 255);
  EXPECT_EQ(image.at(0, 1), 10);
}

TEST(PngImage, OneBitAndSixteenBitGreyBecomeEightBit) {
  TempDir dir;
  writePng(dir.path() / "bw.png", {.width = 8, .height = 1, .bit_depth = 1, .rows = {0b10110000}});
  EXPECT_EQ(readPngGray(dir.path() / "bw.png").pixels, (std::vector<std::uint8_t>{255, 0, 255, 255, 0, 0, 0, 0}));

  writePng(dir.path() / "deep.png", {.width = 2, .height = 1, .bit_depth = 16, .rows = {0xff, 0xff, 0, 0}});
  EXPECT_EQ(readPngGray(dir.path() / "deep.png").pixels, (std::vector<std::uint8_t>{255, 0}));
}

TEST(PngImage, RgbaBecomesLuminanceOverBlack) {
  TempDir dir;
  const fs::path file = dir.path() / "rgba.png";
  writePng(file, {.width = 5,
                  .height = 1,
                  .color_type = PNG_COLOR_TYPE_RGB_ALPHA,
                  .rows = {
                      255, 255, 255, 255,  // opaque white: rock
                      0,   0,   0,   255,  // opaque black: air
                      255, 255, 255, 0,    // transparent white: air, not rock
                      255, 0,   0,   255,  // opaque red: a luminance, not the red channel
                      255, 255, 255, 128,  // half-transparent white: in between
                  }});
  const GrayImage image = readPngGray(file);
  ASSERT_EQ(image.pixels.size(), 5u);
  EXPECT_EQ(image.at(0, 0), 255);
  EXPECT_EQ(image.at(1, 0), 0);
  EXPECT_EQ(image.at(2, 0), 0);
  EXPECT_GT(image.at(3, 0), 60);
  EXPECT_LT(image.at(3, 0), 200);
  EXPECT_GT(image.at(4, 0), 0);
  EXPECT_LT(image.at(4, 0), 255);
}

TEST(PngImage, PaletteWithTransparencyIsResolved) {
  TempDir dir;
  const fs::path file = dir.path() / "palette.png";
  writePng(file, {.width = 4,
                  .height = 1,
                  .color_type = PNG_COLOR_TYPE_PALETTE,
                  .bit_depth = 2,
                  .rows = {0b00011011},  // indices 0, 1, 2, 3
                  .palette = {{0, 0, 0}, {255, 255, 255}, {255, 255, 255}, {128, 128, 128}},
                  .palette_alpha = {255, 255, 0, 255}});
  const GrayImage image = readPngGray(file);
  EXPECT_EQ(image.pixels, (std::vector<std::uint8_t>{0, 255, 0, 128}));
}

TEST(PngImage, MissingFileThrowsWithThePath) {
  TempDir dir;
  const fs::path file = dir.path() / "nowhere.png";
  expectRuntimeErrorMentioning([&] { readPngGray(file); }, file.string());
  expectRuntimeErrorMentioning([&] { readPngGray(file); }, "No such file");
}

TEST(PngImage, NotAPngThrowsWithThePath) {
  TempDir dir;
  const fs::path file = dir.path() / "profile.png";
  writeText(file, "this is a text file with a .png name, as artists sometimes produce\n");
  expectRuntimeErrorMentioning([&] { readPngGray(file); }, file.string());
}

TEST(PngImage, TruncatedPngThrowsWithThePath) {
  TempDir dir;
  const fs::path file = dir.path() / "cut.png";
  PngSpec spec{.width = 64, .height = 64};
  std::mt19937 random(7);  // noise, so the compressed data is long enough to cut
  for (int i = 0; i < 64 * 64; ++i) spec.rows.push_back(png_byte(random()));
  writePng(file, spec);
  const std::string whole = readBytes(file);
  writeText(file, whole.substr(0, whole.size() / 2));
  expectRuntimeErrorMentioning([&] { readPngGray(file); }, file.string());

  std::string corrupt = whole;  // flip bytes inside IDAT: the CRC check fails
  for (std::size_t i = whole.size() / 2; i < whole.size() / 2 + 16; ++i) corrupt[i] = char(~corrupt[i]);
  writeText(file, corrupt);
  expectRuntimeErrorMentioning([&] { readPngGray(file); }, file.string());
}

// ---------------------------------------------------------------- VDB

// Sizes that are not multiples of 8, a solid 8³ block (it becomes a tile), and
// a random mix elsewhere.
VoxelRock randomRock(int nx, int ny, int nz, unsigned seed) {
  VoxelRock rock = test::randomRock(nx, ny, nz, seed);
  const GridLayout& g = rock.layout;
  for (int z = 0; z < std::min(nz, 8); ++z)
    for (int y = 8; y < std::min(ny, 16); ++y)
      for (int x = 8; x < std::min(nx, 16); ++x) {
        rock.material[g.index(x, y, z)] = Material::Rock;
        rock.durability.set(g.index(x, y, z), 1.5f);
      }
  return rock;
}

// A sphere of rock with a little noise: a realistic, mostly sparse shape.
VoxelRock sphereRock(int n) {
  VoxelRock rock = randomRock(n, n, n, 1);
  const GridLayout& g = rock.layout;
  std::mt19937 random(11);
  for (int z = 0; z < n; ++z) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const double dx = x - n / 2.0, dy = y - n / 2.0, dz = z - n / 2.0;
        const bool inside = std::sqrt(dx * dx + dy * dy + dz * dz) < 0.4 * n + (random() % 3);
        const std::size_t cell = g.index(x, y, z);
        rock.material[cell] = inside ? Material::Rock : (z < 2 ? Material::Colluvium : Material::Air);
        rock.durability.set(cell, inside ? 0.5f + float(z) / float(n) : 0.0f);
      }
    }
  }
  return rock;
}

template <typename GridT>
typename GridT::Ptr readGrid(const fs::path& file, const std::string& name) {
  openvdb::initialize();
  openvdb::io::File vdb(file.string());
  vdb.open(false);
  auto grid = openvdb::gridPtrCast<GridT>(vdb.readGrid(name));
  vdb.close();
  return grid;
}

TEST(RockVdb, RoundTripsMaterialsAndDurability) {
  TempDir dir;
  const VoxelRock rock = randomRock(21, 19, 13, 5);
  const fs::path file = dir.path() / "out" / "rock.vdb";
  writeRockVdb(rock, file);
  EXPECT_EQ(folderEntries(file.parent_path()), std::vector<std::string>{"rock.vdb"});

  const VoxelRock back = readRockVdb(file, rock.layout);
  EXPECT_TRUE(back.material == rock.material);
  EXPECT_TRUE(back.durability.toDense() == rock.durability.toDense());
  EXPECT_TRUE(back.integrity.toDense() == std::vector<float>(rock.layout.cellCount(), 1.0f));
}

TEST(RockVdb, LevelSetIsNegativeInsideAndPositiveOutside) {
  TempDir dir;
  // A random mix (every voxel near a surface) and a sphere (deep interior beyond the band).
  for (const VoxelRock& rock : {randomRock(21, 19, 13, 9), sphereRock(40)}) {
    const fs::path file = dir.path() / "rock.vdb";
    writeRockVdb(rock, file);
    const auto sdf = readGrid<openvdb::FloatGrid>(file, "rock_sdf");
    ASSERT_TRUE(sdf);
    EXPECT_EQ(sdf->getGridClass(), openvdb::GRID_LEVEL_SET);
    const auto accessor = sdf->getConstAccessor();
    const GridLayout& g = rock.layout;
    int wrong = 0;
    for (int z = -2; z < g.nz + 2; ++z) {
      for (int y = -2; y < g.ny + 2; ++y) {
        for (int x = -2; x < g.nx + 2; ++x) {
          const bool is_rock = g.contains(x, y, z) && rock.material[g.index(x, y, z)] == Material::Rock;
          const float distance = accessor.getValue(openvdb::Coord(x, y, z));
          if (is_rock ? !(distance < 0.0f) : !(distance > 0.0f)) ++wrong;
        }
      }
    }
    EXPECT_EQ(wrong, 0) << g.nx << "x" << g.ny << "x" << g.nz;
  }
}

TEST(RockVdb, TransformMapsIndicesToVoxelCentresAroundThePivot) {
  TempDir dir;
  const VoxelRock rock = randomRock(21, 19, 13, 3);
  const fs::path file = dir.path() / "rock.vdb";
  writeRockVdb(rock, file);
  // The asset's frame: the footprint's centre on the ground is the origin, as for the meshes.
  const std::array<double, 3> pivot = footprintPivot(rock);
  for (const char* name : {"rock", "colluvium", "durability", "rock_sdf"}) {
    openvdb::initialize();
    openvdb::io::File vdb(file.string());
    vdb.open(false);
    const openvdb::GridBase::Ptr grid = vdb.readGrid(name);
    vdb.close();
    ASSERT_TRUE(grid) << name;
    for (const auto& [i, j, k] : {std::array{0, 0, 0}, std::array{20, 18, 12}, std::array{3, 7, 11}}) {
      const openvdb::Vec3d world = grid->transform().indexToWorld(openvdb::Coord(i, j, k));
      const Vec3d centre = rock.layout.center(i, j, k);
      for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(world[axis], centre[axis] - pivot[axis], 1e-12) << name;
    }
  }
}

TEST(RockVdb, FileMetadataNamesTheCreatorAndVoxelSize) {
  TempDir dir;
  const VoxelRock rock = randomRock(9, 9, 9, 1);
  const fs::path file = dir.path() / "rock.vdb";
  writeRockVdb(rock, file);
  openvdb::initialize();
  openvdb::io::File vdb(file.string());
  vdb.open(false);
  const auto metadata = vdb.getMetadata();
  vdb.close();
  EXPECT_EQ(metadata->metaValue<std::string>("creator"), "rockbake");
  EXPECT_EQ(metadata->metaValue<double>("voxel_size"), rock.layout.h);
}

TEST(RockVdb, SameRockGivesIdenticalBytesAndAHashedUuid) {
  TempDir dir;
  const VoxelRock rock = randomRock(21, 19, 13, 4);
  writeRockVdb(rock, dir.path() / "a.vdb");
  writeRockVdb(rock, dir.path() / "b.vdb");
  const std::string a = readBytes(dir.path() / "a.vdb");
  EXPECT_EQ(a, readBytes(dir.path() / "b.vdb"));
  // The header's UUID field is still a well-formed (version 8) UUID.
  const std::regex uuid("[0-9a-f]{8}-[0-9a-f]{4}-8[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}");
  EXPECT_TRUE(std::regex_match(a.substr(21, 36), uuid)) << a.substr(21, 36);

  VoxelRock other = rock;  // one voxel different: a different file and UUID
  other.durability.set(other.layout.index(8, 8, 0), other.durability[other.layout.index(8, 8, 0)] + 0.5f);
  writeRockVdb(other, dir.path() / "c.vdb");
  EXPECT_NE(readBytes(dir.path() / "c.vdb").substr(21, 36), a.substr(21, 36));
}

// The studio serves rock.vdb from memory: the same bytes as the file, written
// after whatever the stream already holds.
TEST(RockVdb, AStreamGetsTheFilesBytes) {
  TempDir dir;
  const VoxelRock rock = randomRock(21, 19, 13, 4);
  writeRockVdb(rock, dir.path() / "a.vdb");
  std::ostringstream out;
  out << "prefix";
  writeRockVdb(rock, out);
  EXPECT_EQ(out.str(), "prefix" + readBytes(dir.path() / "a.vdb"));
}

TEST(RockVdb, BytesDoNotDependOnTheThreadCount) {
  TempDir dir;
  const VoxelRock rock = sphereRock(72);
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    writeRockVdb(rock, dir.path() / "one.vdb");
  }
  {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    writeRockVdb(rock, dir.path() / "two.vdb");
  }
  writeRockVdb(rock, dir.path() / "default.vdb");
  const std::string one = readBytes(dir.path() / "one.vdb");
  EXPECT_EQ(one, readBytes(dir.path() / "two.vdb"));
  EXPECT_EQ(one, readBytes(dir.path() / "default.vdb"));
}

TEST(RockVdb, ReadRejectsMissingGridsUnreadableFilesAndOtherLayouts) {
  TempDir dir;
  const VoxelRock rock = randomRock(10, 10, 10, 2);

  const fs::path missing = dir.path() / "missing.vdb";
  expectRuntimeErrorMentioning([&] { readRockVdb(missing, rock.layout); }, missing.string());

  const fs::path text = dir.path() / "text.vdb";
  writeText(text, "not a vdb");
  expectRuntimeErrorMentioning([&] { readRockVdb(text, rock.layout); }, text.string());

  const fs::path only_rock = dir.path() / "only_rock.vdb";
  openvdb::initialize();
  auto grid = openvdb::BoolGrid::create(false);
  grid->setName("rock");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(rock.layout.h));
  const Vec3d first = rock.layout.center(0, 0, 0);
  grid->transform().postTranslate(openvdb::Vec3d(first[0], first[1], first[2]));
  openvdb::io::File(only_rock.string()).write(openvdb::GridPtrVec{grid});
  expectRuntimeErrorMentioning([&] { readRockVdb(only_rock, rock.layout); }, "colluvium");

  const fs::path good = dir.path() / "rock.vdb";
  writeRockVdb(rock, good);
  GridLayout finer = rock.layout;
  finer.h /= 2;
  expectRuntimeErrorMentioning([&] { readRockVdb(good, finer); }, "different grid layout");
  GridLayout smaller = rock.layout;
  smaller.nx = 4;
  expectRuntimeErrorMentioning([&] { readRockVdb(good, smaller); }, "outside");
}

}  // namespace
}  // namespace rockbake
