// Preset loading and validation (docs/libraries.md, docs/preset-reference.md).
#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "pipeline/read_inputs.h"
#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "preset/preset_overrides.h"
#include "sim/grid_layout.h"
#include "test_support.h"

namespace rockbake {
namespace {

const char* kFull = R"(rockbake: 1
name: goblin
seed: 7
grid:
  size: [4.0, 4.0, 6.0]
  resolution: 96
  ground: true
shape:
  cylinder: {radius: 1.0, height: 3.0}
  center: [2.0, 2.0, 0.0]
durability:
  points: [[0.0, 2.0], [0.4, 0.6], [0.7, 3.0], [1.0, 1.5]]
  noise:
    - {amplitude: 0.3, period: 0.8, octaves: 3}
    - null
    - {amplitude: 0.5, period: 0.5, octaves: 2}
  keyframes:
    - {at: 2.0, points: [[0.0, 2.0], [0.5, 0.3], [1.0, 1.5]]}
bubbles:
  - up_to: 0.5
    bubble: {sphere: {radius: 0.3}}
    spheroidal: 1.0
    cavernous: 0.0
  - up_to: 1.0
    bubble: {collection: [{bubble: {sphere: {radius: 0.2}}, weight: 1.0},
                          {bubble: {ellipsoid: {radii: [0.5, 0.5, 0.25]}}, weight: 0.5}]}
    spheroidal: 0.6
    cavernous: 0.4
response: {threshold: 0.55}
rockfall: {mode: crumble}
colluvium: {yield: 0.5, talus_angle: 35, removal: 0.1}
time: 3.0
until: {rock_volume_fraction: 0.5}
mesh: {smoothing: 1.0, subdivision: 2, lods: [0.5, 0.25]}
bake: {palette: debug}
export: [ply, glb, collision]
collision: {max_hulls: 8, max_vertices: 32, naming: godot, colluvium: true}
render: {template: studio, width: 640, height: 480, turntable: {frames: 8}}
)";

std::string errorOf(const std::string& yaml, const PresetOverrides& overrides = {}) {
  try {
    parsePreset(yaml, "dir/p.yaml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Preset, ReadsEveryKeyOfTheSchema) {
  const Preset p = parsePreset(kFull, "dir/p.yaml");
  EXPECT_EQ(p.name, "goblin");
  EXPECT_EQ(p.seed, 7u);
  EXPECT_EQ(p.grid.size[2], 6.0);
  EXPECT_EQ(p.grid.resolution, 96);
  ASSERT_TRUE(std::holds_alternative<CylinderShape>(p.shape.kind));
  EXPECT_EQ(std::get<CylinderShape>(p.shape.kind).radius, 1.0);
  ASSERT_TRUE(p.shape.center.has_value());
  ASSERT_EQ(p.durability.graph.points.size(), 4u);
  ASSERT_EQ(p.durability.graph.noise.size(), 3u);
  EXPECT_FALSE(p.durability.graph.noise[1].has_value());
  EXPECT_EQ(p.durability.graph.noise[2]->octaves, 2);
  ASSERT_EQ(p.durability.keyframes.size(), 1u);
  EXPECT_EQ(p.durability.keyframes[0].at, 2.0);
  ASSERT_EQ(p.bubbles.size(), 2u);
  EXPECT_EQ(p.bubbles[1].bubble.kind, BubbleSpec::Kind::Collection);
  EXPECT_EQ(p.bubbles[1].bubble.members[1].bubble.extents[2], 0.25);
  EXPECT_EQ(p.bubbles[1].cavernous, 0.4);
  EXPECT_EQ(p.response.kind, ResponseParams::Kind::Threshold);
  EXPECT_EQ(p.response.value, 0.55);
  EXPECT_EQ(p.rockfall.mode, RockfallMode::Crumble);
  EXPECT_EQ(p.colluvium.removal, 0.1);
  EXPECT_EQ(*p.stop.time, 3.0);
  EXPECT_EQ(*p.stop.rock_volume_fraction, 0.5);
  EXPECT_EQ(p.mesh.lods.size(), 2u);
  EXPECT_EQ(p.bake.palette, Palette::Debug);
  EXPECT_EQ(p.exports, (std::vector<std::string>{"ply", "glb", "collision"}));
  EXPECT_EQ(p.collision.max_hulls, 8);
  EXPECT_EQ(p.collision.max_vertices, 32);
  EXPECT_EQ(p.collision.naming, HullNaming::Godot);
  EXPECT_TRUE(p.collision.colluvium);
  EXPECT_EQ(p.render.turntable_frames, 8);
}

TEST(Preset, FillsDefaults) {
  const Preset p = parsePreset("rockbake: 1\nname: plain\nshape: {box: {size: [1, 1, 1]}}\ncycles: 5\n", "p.yaml");
  EXPECT_EQ(p.grid.resolution, 96);
  EXPECT_TRUE(p.grid.ground);
  EXPECT_EQ(p.durability.graph.points.size(), 2u);
  ASSERT_EQ(p.bubbles.size(), 1u);
  EXPECT_DOUBLE_EQ(p.bubbles[0].bubble.extents[0], 6.0 / 16.0);  // a sixteenth of the longest side
  EXPECT_EQ(p.response.kind, ResponseParams::Kind::Power);
  EXPECT_EQ(p.rockfall.mode, RockfallMode::Drop);
  EXPECT_EQ(*p.stop.cycles, 5);
  EXPECT_FALSE(p.stop.time.has_value());
  EXPECT_EQ(p.exports, (std::vector<std::string>{"ply", "glb", "vdb", "collision"}));
  EXPECT_EQ(p.collision.max_hulls, 16);
  EXPECT_EQ(p.collision.max_vertices, 64);
  EXPECT_EQ(p.collision.naming, HullNaming::Unreal);
  EXPECT_FALSE(p.collision.colluvium);
}

// docs/collision.md, Parameters: each key's range, at its place in the file.
TEST(Preset, CollisionKeysOutOfRangeNameTheirPlace) {
  const std::string base = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ncycles: 5\n";
  const std::string hulls = errorOf(base + "collision:\n  max_hulls: 0\n");
  EXPECT_NE(hulls.find("dir/p.yaml:6:14: collision.max_hulls: must be a whole number from 1 to 100"), std::string::npos)
      << hulls;
  const std::string vertices = errorOf(base + "collision: {max_vertices: 256}\n");
  EXPECT_NE(vertices.find("dir/p.yaml:5:27: collision.max_vertices: must be a whole number from 8 to 255"),
            std::string::npos)
      << vertices;
  const std::string naming = errorOf(base + "collision: {naming: ue5}\n");
  EXPECT_NE(naming.find("dir/p.yaml:5:21: collision.naming: 'ue5' is not one of: unreal, godot"), std::string::npos)
      << naming;
  const std::string format = errorOf(base + "export: [glb, colision]\n");
  EXPECT_NE(format.find("dir/p.yaml:5:15: export.1: 'colision' is not one of: ply, obj, glb, vdb, collision"),
            std::string::npos)
      << format;
  const std::string unknown = errorOf(base + "collision: {max_hull: 4}\n");
  EXPECT_NE(unknown.find("collision.max_hull: unknown key 'max_hull'; did you mean 'max_hulls'?"), std::string::npos)
      << unknown;
}

TEST(Preset, ErrorsNameFileLineColumnAndKeyPath) {
  const std::string base = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ncycles: 5\n";
  // Malformed YAML: the position of the syntax error.
  EXPECT_NE(errorOf("rockbake: 1\nname: [p\n").find("dir/p.yaml:3:"), std::string::npos);
  // Wrong type.
  const std::string wrong_type = errorOf(base + "colluvium:\n  yield: lots\n");
  EXPECT_NE(wrong_type.find("dir/p.yaml:6:10: colluvium.yield: expected a number, found 'lots'"), std::string::npos)
      << wrong_type;
  // Unknown key with a suggestion, at the key.
  const std::string unknown = errorOf(base +
                                      "bubbles:\n  - up_to: 1\n    bubble: {sphere: {radius: 0.2}}\n"
                                      "    spherodial: 1\n");
  EXPECT_NE(unknown.find("dir/p.yaml:8:5: bubbles.0.spherodial: unknown key 'spherodial'; did you mean "
                         "'spheroidal'?"),
            std::string::npos)
      << unknown;
  // Out of range.
  const std::string range = errorOf(base + "colluvium: {talus_angle: 95}\n");
  EXPECT_NE(range.find("dir/p.yaml:5:26: colluvium.talus_angle: must be in (0, 90)"), std::string::npos) << range;
  // Nested list item paths.
  const std::string nested = errorOf(
      base + "bubbles:\n  - up_to: 1\n    bubble: {collection: [{bubble: {sphere: {radius: 0.2}}, weight: -1}]}\n");
  EXPECT_NE(nested.find("bubbles.0.bubble.collection.0.weight: must be greater than 0"), std::string::npos) << nested;
}

TEST(Preset, RejectsInconsistentPresets) {
  const std::string head = "rockbake: 1\nname: p\n";
  const std::string box = "shape: {box: {size: [1, 1, 1]}}\n";
  EXPECT_NE(errorOf(head + box).find("missing 'time'"), std::string::npos);
  EXPECT_NE(errorOf(head + box + "time: 1\ncycles: 3\n").find("not both"), std::string::npos);
  EXPECT_NE(errorOf(head + "shape: {box: {size: [1, 1, 1]}, sphere: {radius: 1}}\ntime: 1\n").find("exactly one"),
            std::string::npos);
  EXPECT_NE(errorOf(head + box +
                    "time: 1\nbubbles:\n  - {up_to: 0.6, bubble: {sphere: {radius: 0.2}}}\n"
                    "  - {up_to: 0.4, bubble: {sphere: {radius: 0.2}}}\n")
                .find("up_to must increase"),
            std::string::npos);
  EXPECT_NE(errorOf(head + box + "time: 1\nbubbles:\n  - {up_to: 0.6, bubble: {sphere: {radius: 0.2}}}\n")
                .find("the last band must reach 1"),
            std::string::npos);
  EXPECT_NE(errorOf(head + box + "time: 1\nbubbles:\n  - {up_to: 1, bubble: {sphere: {radius: 0.001}}}\n")
                .find("smaller than one voxel"),
            std::string::npos);
  EXPECT_NE(errorOf(head + box + "time: 1\ndurability: {points: [[0, 1], [0.5, 1]], noise: [null, null]}\n")
                .find("one entry per segment"),
            std::string::npos);
  EXPECT_NE(errorOf("rockbake: 1\nname: Bad Name\n" + box + "time: 1\n").find("may only use"), std::string::npos);
  EXPECT_NE(errorOf("rockbake: 2\nname: p\n" + box + "time: 1\n")
                .find("dir/p.yaml:1:11: rockbake: schema version 2 is not supported"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "shape: {image: {path: missing.png, height: 1}}\ntime: 1\n").find("shape.image.path"),
            std::string::npos);
}

TEST(Preset, AGridBeyondThisMachinesMemoryIsRefusedAtItsKey) {
  // Valid as a preset; the bake's inputs check refuses it before allocating.
  const Preset huge = parsePreset(
      "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\ngrid: {size: [1, 1, 1], resolution: 2048}\n"
      "bubbles: [{up_to: 1, bubble: {sphere: {radius: 0.01}}}]\n",
      "dir/p.yaml");
  try {
    checkGridFitsInMemory(huge);
    FAIL() << "a 2048³ grid was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dir/p.yaml:5:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("grid.resolution"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("MiB"), std::string::npos) << e.what();
  }
  Preset fine = huge;
  fine.grid.resolution = 32;
  EXPECT_NO_THROW(checkGridFitsInMemory(fine));
}

TEST(Preset, TheMemoryGuardRefusesByTheSimulationsOwnEstimate) {
  const std::string yaml =
      "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n"
      "grid: {size: [1, 1, 1], resolution: 256}\nbubbles: [{up_to: 1, bubble: {sphere: {radius: 0.01}}}]\n";
  Preset p = parsePreset(yaml, "dir/p.yaml");
  const std::uint64_t physical = std::uint64_t(::sysconf(_SC_PHYS_PAGES)) * std::uint64_t(::sysconf(_SC_PAGESIZE));
  // The smallest resolution whose estimate passes 60 % of this machine's memory.
  int refused = 256;
  for (; refused < 8192; refused += refused / 8) {
    p.grid.resolution = refused;
    if (estimateSimulationBytes(computeGridLayout(p)) > physical / 10 * 6) break;
  }
  ASSERT_LT(refused, 8192);
  p.grid.resolution = refused;
  const std::uint64_t needed = estimateSimulationBytes(computeGridLayout(p));
  try {
    checkGridFitsInMemory(p);
    FAIL() << "resolution " << refused << " was accepted";
  } catch (const InputError& e) {
    const std::string error = e.what();
    EXPECT_NE(error.find("grid.resolution"), std::string::npos) << error;
    EXPECT_NE(error.find("needs about " + std::to_string(needed >> 20) + " MiB"), std::string::npos) << error;
  }
  // A little below it the same preset is accepted.
  p.grid.resolution = refused * 7 / 8;
  EXPECT_NO_THROW(checkGridFitsInMemory(p));
}

TEST(Preset, TheMemoryEstimateIsAboutOneBytePerCellPlusEightPerDomainCell) {
  GridLayout g;
  g.nx = 322, g.ny = 322, g.nz = 417, g.margin = 33;  // goblin at resolution 384
  const double cells = double(g.cellCount());
  const double domain = 256.0 * 256.0 * 384.0;
  const double estimate = double(estimateSimulationBytes(g));
  EXPECT_GT(estimate, cells + 8 * domain);
  // Bit planes, the air field and work lists add under a byte a cell and two a
  // domain cell, colluvium's columns a bit a cell; the old layout took 17
  // bytes a cell.
  EXPECT_LT(estimate, 2 * cells + 10 * domain + cells / 8);
  EXPECT_LT(estimate, 17 * cells / 2);
}

TEST(Preset, PaletteColoursAreSrgbHexOrLists) {
  const Preset p = parsePreset(
      "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n"
      "bake:\n  palette: natural\n  layers:\n    - {durability: 0.5, color: '#E3C9A0'}\n"
      "    - {durability: 2.0, color: [0.4, 0.2, 0.1]}\n  colluvium_color: '#b49a78'\n",
      "p.yaml");
  ASSERT_EQ(p.bake.layers.size(), 2u);
  EXPECT_NEAR(p.bake.layers[0].color[0], 0xE3 / 255.0, 1e-12);
  EXPECT_EQ(p.bake.layers[1].color[2], 0.1);
  EXPECT_NEAR((*p.bake.colluvium_color)[1], 0x9a / 255.0, 1e-12);
  const std::string head = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n";
  EXPECT_NE(errorOf(head + "bake: {layers: [{durability: 1, color: 'red'}]}\n").find("'red' is not a colour"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "bake: {layers: [{durability: 1, color: [1, 2, 0]}]}\n")
                .find("bake.layers.0.color.1: must be in [0, 1]"),
            std::string::npos);
  EXPECT_NE(errorOf(head + "bake: {layers: [{durability: 2, color: '#000000'}, {durability: 1, color: '#ffffff'}]}\n")
                .find("durability must increase"),
            std::string::npos);
}

TEST(Preset, ImagePathsResolveAgainstThePresetsFolder) {
  test::TempDir dir;
  test::writeText(dir.path() / "shapes" / "s.png", "not read here");
  const Preset p = parsePreset(
      "rockbake: 1\nname: p\nshape: {image: {path: shapes/s.png, mode: revolve, height: 2}}\n"
      "time: 1\n",
      dir.path() / "p.yaml");
  const auto& image = std::get<ImageShape>(p.shape.kind);
  EXPECT_EQ(image.path, dir.path() / "shapes" / "s.png");
  EXPECT_EQ(image.mode, ImageMode::Revolve);
}

TEST(Preset, SetOverridesApplyBeforeValidation) {
  PresetOverrides o;
  o.sets = {"colluvium.yield=0.3", "export=[ply, glb]", "bubbles.1.spheroidal=0.25", "grid.ground=false", "cycles=4"};
  o.seed = 99;
  o.resolution = 48;
  const Preset p = parsePreset(kFull, "p.yaml", o);
  EXPECT_EQ(p.colluvium.yield, 0.3);
  EXPECT_EQ(p.exports, (std::vector<std::string>{"ply", "glb"}));
  EXPECT_EQ(p.bubbles[1].spheroidal, 0.25);
  EXPECT_FALSE(p.grid.ground);
  EXPECT_EQ(*p.stop.cycles, 4);  // replaces the preset's time
  EXPECT_FALSE(p.stop.time.has_value());
  EXPECT_EQ(p.seed, 99u);
  EXPECT_EQ(p.grid.resolution, 48);

  const auto setError = [](const std::string& set) {
    PresetOverrides bad;
    bad.sets = {set};
    return errorOf(kFull, bad);
  };
  EXPECT_NE(setError("colluvium.yield").find("--set: 'colluvium.yield': expected key.path=VALUE"), std::string::npos);
  EXPECT_NE(setError("bubbles.7.spheroidal=1").find("past the end"), std::string::npos);
  EXPECT_NE(setError("colluvium.yield=[1, 2").find("not valid YAML"), std::string::npos);
  // A bad value that came from --set is located at the flag.
  EXPECT_NE(setError("colluvium.yield=3").find("--set colluvium.yield=3: colluvium.yield: must be in [0, 1]"),
            std::string::npos)
      << setError("colluvium.yield=3");
}

TEST(Preset, MapsFollowACoarserResolution) {
  // The preset's texels per voxel or more, as a power of two between 256 and the preset's size.
  EXPECT_EQ(mapSizeAtResolution(2048, 96, 32), 1024);  // 682.7 → 1024
  EXPECT_EQ(mapSizeAtResolution(2048, 96, 24), 512);
  EXPECT_EQ(mapSizeAtResolution(2048, 96, 8), 256);
  EXPECT_EQ(mapSizeAtResolution(2048, 96, 96), 2048);
  EXPECT_EQ(mapSizeAtResolution(2048, 96, 384), 2048);  // a finer bake keeps the preset's budget
  EXPECT_EQ(mapSizeAtResolution(512, 96, 8), 256);

  const std::string textured =
      "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n"
      "grid: {size: [1, 1, 1], resolution: 96}\ntexture: {size: 2048}\n";
  PresetOverrides preview;
  preview.resolution = 24;
  const Preset p = parsePreset(textured, "p.yaml", preview);
  ASSERT_TRUE(p.texture.has_value());
  EXPECT_EQ(p.texture->size, 512);
  EXPECT_EQ(p.grid.resolution, 24);
  // Where it came from, for messages and the manifest.
  EXPECT_NE(p.locate("texture.size").file.find("maps follow the resolution"), std::string::npos)
      << p.locate("texture.size").file;

  PresetOverrides by_hand = preview;
  by_hand.sets = {"texture.size=4096"};
  EXPECT_EQ(parsePreset(textured, "p.yaml", by_hand).texture->size, 4096);
  PresetOverrides finer;
  finer.resolution = 192;
  EXPECT_EQ(parsePreset(textured, "p.yaml", finer).texture->size, 2048);
  // No texture block: nothing to follow, and none is made.
  const std::string bare = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 1\n";
  EXPECT_FALSE(parsePreset(bare, "p.yaml", preview).texture.has_value());
}

TEST(Preset, ResolvedJsonReadsLikeAPreset) {
  const Preset p = parsePreset(kFull, "p.yaml");
  const nlohmann::json j = presetToJson(p);
  EXPECT_EQ(j["name"], "goblin");
  EXPECT_EQ(j["grid"]["resolution"], 96);
  EXPECT_EQ(j["shape"]["cylinder"]["radius"], 1.0);
  EXPECT_EQ(j["bubbles"][1]["bubble"]["collection"][1]["bubble"]["ellipsoid"]["radii"][0], 0.5);
  EXPECT_EQ(j["response"]["threshold"], 0.55);
  EXPECT_TRUE(j["durability"]["noise"][1].is_null());
  EXPECT_EQ(j["durability"]["keyframes"][0]["at"], 2.0);
  EXPECT_EQ(j["rockfall"]["mode"], "crumble");
  EXPECT_EQ(j["time"], 3.0);
  EXPECT_FALSE(j.contains("cycles"));
  // The dump parses back into the same preset.
  const Preset again = parsePreset(j.dump(), "p.yaml");
  EXPECT_EQ(presetToJson(again), j);
}

// The docs/preset-reference.md example as an artist would write it (minus extends), with its image next to it.
TEST(Preset, ReadsTheSpecExampleWithAnImageShape) {
  test::TempDir dir;
  test::writeText(dir.path() / "shapes" / "goblin.png", "only its existence is checked here");
  std::string yaml = kFull;
  const std::string cylinder = "  cylinder: {radius: 1.0, height: 3.0}\n";
  yaml.replace(yaml.find(cylinder), cylinder.size(),
               "  image: {path: shapes/goblin.png, mode: extrude, height: 5.0}\n");
  const Preset p = parsePreset(yaml, dir.path() / "goblin.yaml");
  ASSERT_TRUE(std::holds_alternative<ImageShape>(p.shape.kind));
  const auto& image = std::get<ImageShape>(p.shape.kind);
  EXPECT_EQ(image.path, dir.path() / "shapes" / "goblin.png");
  EXPECT_TRUE(image.path.is_absolute());
  EXPECT_EQ(image.mode, ImageMode::Extrude);
  EXPECT_EQ(image.height, 5.0);
  EXPECT_EQ(*p.shape.center, (Vec3d{2.0, 2.0, 0.0}));
  EXPECT_EQ(p.file, dir.path() / "goblin.yaml");
  // The resolved JSON names the image by its absolute path.
  EXPECT_EQ(presetToJson(p)["shape"]["image"]["path"], (dir.path() / "shapes" / "goblin.png").string());
}

TEST(Preset, ErrorsPointAtTheOffendingNode) {
  const std::string head = "rockbake: 1\nname: p\n";
  const std::string box = "shape: {box: {size: [1, 1, 1]}}\n";
  // A missing image: at the path value, with the resolved path.
  const std::string missing = errorOf(head + "shape: {image: {path: missing.png, height: 1}}\ntime: 1\n");
  const std::string resolved = (std::filesystem::absolute("dir/p.yaml").parent_path() / "missing.png").string();
  EXPECT_NE(missing.find("dir/p.yaml:3:23: shape.image.path: no image file at " + resolved), std::string::npos)
      << missing;
  // A name too long for the file system: no such file, at the same place.
  const std::string too_long = errorOf(head + "shape: {mesh: {path: " + std::string(300, 'm') + ".obj}}\ntime: 1\n");
  EXPECT_NE(too_long.find("dir/p.yaml:3:22: shape.mesh.path: no mesh file at "), std::string::npos) << too_long;
  // Two shapes: at the shape map.
  const std::string two = errorOf(head + "shape: {box: {size: [1, 1, 1]}, sphere: {radius: 1}}\ntime: 1\n");
  EXPECT_NE(two.find("dir/p.yaml:3:8: shape: has box, sphere; give exactly one of"), std::string::npos) << two;
  // Neither time nor cycles: the preset as a whole.
  const std::string neither = errorOf(head + box);
  EXPECT_NE(neither.find("dir/p.yaml:1:1: missing 'time' (or 'cycles')"), std::string::npos) << neither;
  // Bands out of order: at the second band's up_to.
  const std::string bands = errorOf(head + box +
                                    "time: 1\nbubbles:\n  - {up_to: 0.6, bubble: {sphere: {radius: 0.2}}}\n"
                                    "  - {up_to: 0.4, bubble: {sphere: {radius: 0.2}}}\n");
  EXPECT_NE(bands.find("dir/p.yaml:7:13: bubbles.1.up_to: bands go bottom to top"), std::string::npos) << bands;
  // A bubble below one voxel: at its radius.
  const std::string tiny =
      errorOf(head + box + "time: 1\nbubbles:\n  - {up_to: 1, bubble: {sphere: {radius: 0.001}}}\n");
  EXPECT_NE(tiny.find("dir/p.yaml:6:42: bubbles.0.bubble.sphere.radius: a bubble extent of 0.001 is smaller than "
                      "one voxel"),
            std::string::npos)
      << tiny;
  // Keyframes out of time order: at the later keyframe's at.
  const std::string keyframes = errorOf(head + box +
                                        "time: 1\ndurability:\n  keyframes:\n    - {at: 2, points: [[0, 1]]}\n"
                                        "    - {at: 1, points: [[0, 1]]}\n");
  EXPECT_NE(keyframes.find("dir/p.yaml:8:12: durability.keyframes.1.at: keyframes must be in time order"),
            std::string::npos)
      << keyframes;
  // A required key written without a value: at the key.
  const std::string empty_name = errorOf("rockbake: 1\nname:\n" + box + "time: 1\n");
  EXPECT_NE(empty_name.find("dir/p.yaml:2:1: name: missing 'name'"), std::string::npos) << empty_name;
  // A base preset that is not there: at the extends value, with the path it looked at.
  const std::string extends = errorOf(head + box + "time: 1\nextends: base.yaml\n");
  EXPECT_NE(extends.find("dir/p.yaml:5:10: extends: no base preset at " +
                         (std::filesystem::absolute("dir") / "base.yaml").string()),
            std::string::npos)
      << extends;
}

TEST(Preset, RejectsWhatYamlWouldSilentlyDrop) {
  const std::string base = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ncycles: 5\n";
  // yaml-cpp keeps the first of two equal keys: the second would be ignored.
  const std::string twice = errorOf(base + "colluvium:\n  yield: 0.2\n  yield: 0.8\n");
  EXPECT_NE(twice.find("dir/p.yaml:7:3: colluvium.yield: 'yield' is given twice (first on line 6)"), std::string::npos)
      << twice;
  const std::string documents = errorOf(base + "---\nseed: 3\n");
  EXPECT_NE(documents.find("dir/p.yaml:6:1: a preset holds one YAML document"), std::string::npos) << documents;
  // A list as a key is an InputError too (exit status 2), not a yaml-cpp conversion error.
  EXPECT_NE(errorOf(base + "grid: {[1]: 2}\n").find("dir/p.yaml:5:8: grid: expected a key name, found a list"),
            std::string::npos);
}

TEST(Preset, DefaultBubbleFitsEveryAllowedResolution) {
  const std::string plain = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ncycles: 5\n";
  for (const int resolution : {8, 16, 96, 1024}) {
    PresetOverrides o;
    o.resolution = resolution;
    const Preset p = parsePreset(plain, "p.yaml", o);
    const double h = 6.0 / resolution;
    ASSERT_EQ(p.bubbles.size(), 1u);
    EXPECT_GE(p.bubbles[0].bubble.extents[0], h) << resolution;
    EXPECT_LE(p.bubbles[0].bubble.extents[0], 48 * h) << resolution;
  }
}

TEST(Preset, SetCreatesKeysAndChecksPaths) {
  const std::string base = "rockbake: 1\nname: p\nshape: {box: {size: [1, 1, 1]}}\ntime: 2\n";
  PresetOverrides create;
  create.sets = {"until.rock_volume_fraction=0.4", "shape.box.size.2=3", "render.turntable.frames=12"};
  const Preset p = parsePreset(base, "p.yaml", create);
  EXPECT_EQ(*p.stop.rock_volume_fraction, 0.4);
  EXPECT_EQ(std::get<BoxShape>(p.shape.kind).size[2], 3.0);
  EXPECT_EQ(p.render.turntable_frames, 12);
  EXPECT_EQ(*p.stop.time, 2.0);

  const auto setError = [&](const std::string& set) {
    PresetOverrides bad;
    bad.sets = {set};
    return errorOf(base, bad);
  };
  EXPECT_NE(setError("shape.box.size.1abc=3").find("--set: 'shape.box.size.1abc=3': '1abc' must be a list index"),
            std::string::npos);
  EXPECT_NE(setError("name.first=x").find("--set: 'name.first=x': 'first' cannot be set inside a value"),
            std::string::npos);
  EXPECT_NE(setError("colluvium..yield=1").find("empty part"), std::string::npos);
  // Values the flag introduced are reported at the flag, even when they remove a required key.
  EXPECT_NE(setError("name=").find("--set name=: name: missing 'name'"), std::string::npos);
  EXPECT_NE(setError("colluvum.yield=0.3")
                .find("--set colluvum.yield=0.3: colluvum: unknown key 'colluvum'; "
                      "did you mean 'colluvium'?"),
            std::string::npos);
  PresetOverrides low;
  low.resolution = 4;
  EXPECT_NE(errorOf(base, low).find("--resolution 4: grid.resolution: must be a whole number from 8 to 2048"),
            std::string::npos);
}

TEST(Preset, ResolvedJsonHasEveryKeyWithDefaults) {
  const nlohmann::json j =
      presetToJson(parsePreset("rockbake: 1\nname: plain\nshape: {sphere: {radius: 1}}\ncycles: 5\n", "p.yaml"));
  for (const char* key : {"rockbake", "name", "seed", "grid", "shape", "durability", "bubbles", "response", "rockfall",
                          "colluvium", "cycles", "mesh", "bake", "export", "collision", "render"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_FALSE(j.contains("time"));
  EXPECT_FALSE(j.contains("until"));
  EXPECT_EQ(j["cycles"], 5);
  EXPECT_EQ(j["durability"]["points"], nlohmann::json::parse("[[0.0, 1.0], [1.0, 1.0]]"));
  EXPECT_EQ(j["bubbles"][0]["bubble"]["sphere"]["radius"], 6.0 / 16.0);
  EXPECT_EQ(j["response"]["power"], 1.0);
  EXPECT_TRUE(j["shape"]["center"].is_null());
  EXPECT_EQ(j["export"], nlohmann::json::parse(R"(["ply", "glb", "vdb", "collision"])"));
  EXPECT_EQ(j["collision"],
            nlohmann::json::parse(R"({"max_hulls": 16, "max_vertices": 64, "naming": "unreal", "colluvium": false})"));
  // Deterministic, and it loads back to itself.
  EXPECT_EQ(presetToJson(parsePreset(j.dump(), "p.yaml")).dump(), j.dump());
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

// The reader is the schema: the JSON that `preset show` and stats.json write
// reads back as the same preset, so the writer names no key the reader does
// not know, and leaves out nothing it does.
TEST(Preset, ItsJsonReadsBackAsTheSamePreset) {
  int presets = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::sourceDir() / "presets")) {
    if (entry.path().extension() != ".yaml" || entry.path().stem() == "base" || entry.path().stem() == "library")
      continue;
    const Preset preset = loadPreset(entry.path());
    const nlohmann::json json = presetToJson(preset);
    const Preset again = parsePreset(json.dump(), entry.path());
    EXPECT_EQ(presetToJson(again), json) << entry.path();
    ++presets;
  }
  EXPECT_GE(presets, 10);
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

// render.turntable.fps and .lookdev (docs/preset-reference.md): read, defaulted,
// range-checked at their line, and in the resolved preset only with a turntable
// (so bakes without one keep their input hashes).
TEST(Preset, TurntableMovieRateAndLookdev) {
  const std::string head = std::string(test::kSmallPreset);
  Preset p = parsePreset(head + "render: {turntable: {frames: 6, fps: 30, lookdev: true}}\n", "dir/p.yaml");
  EXPECT_EQ(p.render.turntable_fps, 30);
  EXPECT_TRUE(p.render.turntable_lookdev);
  EXPECT_EQ(presetToJson(p)["render"]["turntable"]["fps"], 30);
  EXPECT_EQ(presetToJson(p)["render"]["turntable"]["lookdev"], true);
  p = parsePreset(head + "render: {turntable: {frames: 6}}\n", "dir/p.yaml");
  EXPECT_EQ(p.render.turntable_fps, 24);
  EXPECT_FALSE(p.render.turntable_lookdev);
  p = parsePreset(head, "dir/p.yaml");
  // The resolved preset names every key, defaults included, as the schema writes them.
  EXPECT_EQ(presetToJson(p)["render"]["turntable"]["fps"], 24);
  EXPECT_EQ(presetToJson(p)["render"]["turntable"]["lookdev"], false);
  const std::string bad = errorOf(head + "render: {turntable: {frames: 6, fps: 0}}\n");
  EXPECT_NE(bad.find("p.yaml:13"), std::string::npos) << bad;
  EXPECT_NE(bad.find("render.turntable.fps"), std::string::npos) << bad;
  EXPECT_NE(errorOf(head + "render: {turntable: {lookdev: maybe}}\n").find("render.turntable.lookdev"),
            std::string::npos);
}

}  // namespace
}  // namespace rockbake
