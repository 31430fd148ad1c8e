// The texture set in the bake, through the real executable (docs/textures.md, docs/formats.md):
// the `texture:` block, --no-textures, the files and what names them.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using test::readBytes;
using test::runRockbake;
using test::TempDir;
using test::writeText;

// The small preset with colluvium, two LODs, OBJ and GLB, and a small texture set.
std::string texturedPreset() {
  return std::string(test::kSmallPreset) +
         "colluvium: {yield: 0.6}\n"
         "mesh: {subdivision: 1, lods: [0.5, 0.25]}\n"
         "export: [obj, glb]\n"
         "texture: {size: 256, ao_rays: 4}\n";
}

// Every file under `folder`, by path relative to it, with its bytes.
std::map<std::string, std::string> filesUnder(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(folder))
    if (e.is_regular_file()) files[fs::relative(e.path(), folder).string()] = readBytes(e.path());
  return files;
}

TEST(TextureBake, MapsAndMeshesAreByteIdenticalAtOneAndTwoThreads) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", texturedPreset());
  std::map<std::string, std::string> outputs[2];
  for (int threads : {1, 2}) {
    const fs::path out = dir.path() / ("t" + std::to_string(threads));
    const auto result = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-render",
                                     "--threads", std::to_string(threads)});
    ASSERT_EQ(result.exit_status, 0) << result.output;
    outputs[threads - 1] = filesUnder(out / "small" / "textures");
    for (const char* mesh : {"rock.glb", "rock_lod1.glb", "rock_lod2.glb", "rock.obj", "rock.mtl"})
      outputs[threads - 1][mesh] = readBytes(out / "small" / mesh);
  }
  // LOD0: base colour, normal, ORM, height, mask; LOD1 and LOD2: all but the height.
  EXPECT_EQ(outputs[0].size(), 5u + 4u + 4u + 5u);
  for (const char* file : {"small_BaseColor.png", "small_Normal_LOD0.png", "small_ORM.png", "small_Height.exr",
                           "small_Mask.png", "small_BaseColor_LOD1.png", "small_Normal_LOD2.png", "small_ORM_LOD2.png"})
    EXPECT_TRUE(outputs[0].count(file)) << file;
  for (const auto& [file, bytes] : outputs[0]) {
    ASSERT_TRUE(outputs[1].count(file)) << file;
    EXPECT_TRUE(bytes == outputs[1].at(file)) << file << ": 1 vs 2 threads differ";
  }
}

TEST(TextureBake, AssetJsonObjAndStatsDescribeTheSet) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", texturedPreset());
  const fs::path out = dir.path() / "out";
  const auto result = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-render"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const fs::path asset = out / "small";
  const auto json = nlohmann::json::parse(readBytes(asset / "asset.json"));
  // Halved per LOD below LOD0, at least 256: every LOD's maps at 256 here.
  ASSERT_EQ(json["lods"].size(), 3u);
  for (const auto& lod : json["lods"]) {
    EXPECT_EQ(lod["map_size"], 256);
    EXPECT_GT(lod["texel_density"].get<double>(), 0.0);
  }
  std::map<std::string, int> per_type;
  for (const auto& m : json["maps"]) {
    ++per_type[m["type"].get<std::string>()];
    EXPECT_TRUE(fs::is_regular_file(asset / m["file"].get<std::string>())) << m["file"];
    const std::string space = m["colour_space"];
    EXPECT_EQ(space, m["type"] == "base_color" ? "srgb" : "linear") << m["file"];
  }
  EXPECT_EQ(per_type,
            (std::map<std::string, int>{{"base_color", 3}, {"height", 1}, {"mask", 3}, {"normal", 3}, {"orm", 3}}));
  // The OBJ: texture coordinates on every face corner, the maps in the MTL.
  const std::string obj = readBytes(asset / "rock.obj"), mtl = readBytes(asset / "rock.mtl");
  EXPECT_NE(obj.find("\nvt "), std::string::npos);
  EXPECT_EQ(obj.find("//"), std::string::npos) << "a face without its texture coordinate";
  EXPECT_NE(mtl.find("map_Kd textures/small_BaseColor.png"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("map_Bump -bm 1 textures/small_Normal_LOD0.png"), std::string::npos) << mtl;
  // The texture phase is timed, between the mesh stage and the exports.
  const auto stats = nlohmann::json::parse(readBytes(asset / "stats.json"));
  EXPECT_GT(stats["stages"]["texture"].get<double>(), 0.0);
  // The manifest lists the maps among the outputs.
  const auto manifest = nlohmann::json::parse(readBytes(asset / "manifest.json"));
  bool listed = false;
  for (const auto& o : manifest["outputs"]) listed = listed || o["path"] == "textures/small_ORM_LOD2.png";
  EXPECT_TRUE(listed);
}

TEST(TextureBake, NoTexturesMakesNoneAndChangesTheInputHash) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", texturedPreset());
  const fs::path out = dir.path() / "out";
  ASSERT_EQ(runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-render"}).exit_status,
            0);
  const std::string textured_hash = nlohmann::json::parse(readBytes(out / "small" / "asset.json"))["input_hash"];
  const auto result =
      runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-render", "--no-textures"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  // The bake replaces the folder: the earlier texture set goes with it.
  EXPECT_FALSE(fs::exists(out / "small" / "textures"));
  const auto json = nlohmann::json::parse(readBytes(out / "small" / "asset.json"));
  EXPECT_FALSE(json.contains("maps"));
  EXPECT_NE(json["input_hash"], textured_hash);
  const std::string glb = readBytes(out / "small" / "rock.glb");
  EXPECT_EQ(glb.find("TEXCOORD_0"), std::string::npos);
  EXPECT_EQ(glb.find("baseColorTexture"), std::string::npos);
  EXPECT_EQ(readBytes(out / "small" / "rock.obj").find("\nvt "), std::string::npos);
}

// Maps no glTF material names (the mask, the height) are still read through the LOD's atlas: every
// LOD whose mask map is written has TEXCOORD_0 in its GLB, and the OBJ its vt.
TEST(TextureBake, AMaskOrHeightAloneStillGivesEveryLodItsUvs) {
  TempDir dir;
  std::string preset = texturedPreset();
  preset.replace(preset.find("texture: {size: 256, ao_rays: 4}"),
                 std::string("texture: {size: 256, ao_rays: 4}").size(),
                 "texture: {size: 256, ao_rays: 4, maps: [mask, height]}");
  writeText(dir.path() / "small.yaml", preset);
  const fs::path out = dir.path() / "out";
  const auto result = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out.string(), "--no-render"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const fs::path asset = out / "small";
  EXPECT_TRUE(fs::exists(asset / "textures" / "small_Height.exr"));
  for (const auto& [glb, mask] :
       {std::pair{"rock.glb", "small_Mask.png"}, std::pair{"rock_lod1.glb", "small_Mask_LOD1.png"},
        std::pair{"rock_lod2.glb", "small_Mask_LOD2.png"}}) {
    ASSERT_TRUE(fs::exists(asset / "textures" / mask)) << mask;
    const std::string bytes = readBytes(asset / glb);
    EXPECT_NE(bytes.find("TEXCOORD_0"), std::string::npos) << glb << " has no uvs for " << mask;
    EXPECT_EQ(bytes.find("baseColorTexture"), std::string::npos) << glb;
  }
  EXPECT_NE(readBytes(asset / "rock.obj").find("\nvt "), std::string::npos);
}

// Gutters that leave the charts almost no texels are warned about, naming the key, and gutters
// the charts cannot fit beside are bad input; the house padding is neither.
TEST(TextureBake, GuttersThatTakeTheMapAreWarnedAbout) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", texturedPreset());
  const auto bake = [&](const std::string& padding, const std::string& toe = "12") {
    return runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", (dir.path() / "out").string(),
                        "--no-render", "--set", "texture.padding=" + padding, "--set", "mesh.apron_toe=" + toe});
  };
  // Gutters the charts fit beside at no density: bad input at the key, exit 2, no asset. (Without
  // the apron's toe: with it, this small rock's charts just fit beside 64-texel gutters.)
  const auto none = bake("64", "0");
  EXPECT_EQ(none.exit_status, 2) << none.output;
  EXPECT_NE(none.output.find("--set texture.padding=64: texture.padding: cannot pack"), std::string::npos)
      << none.output;
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "small")) << "a half-written asset was left";
  const auto wide = bake("48");
  ASSERT_EQ(wide.exit_status, 0) << wide.output;
  EXPECT_NE(wide.output.find("small: LOD0's charts cover "), std::string::npos) << wide.output;
  EXPECT_NE(wide.output.find("(texture.padding 48) take the rest; lower texture.padding or raise texture.size"),
            std::string::npos)
      << wide.output;
  const auto house = bake("8");
  ASSERT_EQ(house.exit_status, 0) << house.output;
  EXPECT_EQ(house.output.find("charts cover"), std::string::npos) << house.output;
}

// Maps are bounded by what the bake source can fill: a few hundred triangles do not get 8192² maps
// (texture_params.h, usefulMapSize), and the log says why the size differs from texture.size.
TEST(TextureBake, MapsAreBoundedByWhatTheSurfaceCanFill) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", std::string(test::kSmallPreset) +
                                           "mesh: {subdivision: 0, lods: []}\nexport: [glb]\n"
                                           "texture: {size: 8192, lod_size: full, ao_rays: 4}\n");
  const auto result =
      runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", (dir.path() / "out").string(), "--no-render"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  const auto json = nlohmann::json::parse(readBytes(dir.path() / "out" / "small" / "asset.json"));
  const int size = json["lods"][0]["map_size"].get<int>();
  EXPECT_LE(size, 1024) << "a small source baked at the full 8192";
  EXPECT_GE(size, 256);
  EXPECT_NE(result.output.find("not texture.size 8192: the bake source's "), std::string::npos) << result.output;
}

TEST(TextureBake, LibraryAndResumeTakeNoTexturesToo) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", texturedPreset());
  writeText(dir.path() / "lib.yaml", "- preset: small.yaml\n");
  const fs::path out = dir.path() / "out";
  // A library with --no-textures: no texture set; the same library without it is not
  // taken for done (the input hash counts the texture block) and bakes one.
  auto result =
      runRockbake({"library", (dir.path() / "lib.yaml").string(), "-o", out.string(), "--no-render", "--no-textures"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  ASSERT_EQ(fs::exists(out / "small" / "manifest.json"), true) << result.output;
  EXPECT_FALSE(fs::exists(out / "small" / "textures"));
  result = runRockbake({"library", (dir.path() / "lib.yaml").string(), "-o", out.string(), "--no-render"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  EXPECT_TRUE(fs::is_regular_file(out / "small" / "textures" / "small_BaseColor.png"));

  // resume from a checkpoint of the textured bake, without textures and with them.
  const fs::path baked = dir.path() / "baked";
  result = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", baked.string(), "--no-render",
                        "--checkpoint-every", "0.25"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  fs::path checkpoint;
  for (const auto& e : fs::directory_iterator(baked / "small" / "checkpoints")) checkpoint = e.path();
  ASSERT_FALSE(checkpoint.empty());
  const fs::path plain = dir.path() / "plain", textured = dir.path() / "textured";
  result = runRockbake({"resume", checkpoint.string(), "-o", plain.string(), "--no-render", "--no-textures"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  EXPECT_FALSE(fs::exists(plain / "small" / "textures"));
  result = runRockbake({"resume", checkpoint.string(), "-o", textured.string(), "--no-render"});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  EXPECT_TRUE(fs::is_regular_file(textured / "small" / "textures" / "small_ORM.png"));
}

TEST(TextureBake, BadTextureKeysExitTwoNamingTheKey) {
  TempDir dir;
  writeText(dir.path() / "small.yaml", texturedPreset());
  const auto out = (dir.path() / "out").string();
  const auto size = runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out, "--set", "texture.size=300"});
  EXPECT_EQ(size.exit_status, 2);
  EXPECT_NE(size.output.find("texture.size"), std::string::npos) << size.output;
  EXPECT_NE(size.output.find("power of two"), std::string::npos) << size.output;
  const auto maps =
      runRockbake({"bake", (dir.path() / "small.yaml").string(), "-o", out, "--set", "texture.maps=[normal, normal]"});
  EXPECT_EQ(maps.exit_status, 2);
  EXPECT_NE(maps.output.find("listed twice"), std::string::npos) << maps.output;
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "small"));
}

}  // namespace
}  // namespace rockbake
