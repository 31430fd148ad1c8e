// rockbake blender-library's checks and catalogues without Blender (docs/libraries.md, "Blender's
// asset browser"): the catalogue of a job, the catalogue file and its UUIDs, which folders are
// bakes, which output folders may be written, and how Blender is found. Blender itself writes the
// library in tests/delivery/blender_library_test.sh.
#include <sys/stat.h>

#include <fstream>
#include <regex>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "delivery/baked_assets.h"
#include "delivery/blender_catalogs.h"
#include "delivery/blender_library.h"
#include "delivery/blender_program.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::TempDir;
using test::writeText;

json libraryInputs(const std::string& name, json seed, json wedge) {
  return {{"job", {{"name", name}, {"preset", "presets/goblin.yaml"}, {"seed", seed}, {"wedge", wedge}}},
          {"library", {{"file", "lib.yaml"}, {"sha256", "00"}}},
          {"seed", 7}};
}

TEST(BlenderCatalogs, TheCatalogueIsTheLibraryEntryAndItsWedge) {
  EXPECT_EQ(catalogPathForJob(libraryInputs("goblin-s2", 2, nullptr)), "goblin");
  EXPECT_EQ(catalogPathForJob(libraryInputs("goblin-tall-s2", 2, "tall")), "goblin/tall");
  EXPECT_EQ(catalogPathForJob(libraryInputs("cube-soft", nullptr, "soft")), "cube/soft");
  EXPECT_EQ(catalogPathForJob(libraryInputs("cube", nullptr, nullptr)), "cube");
  // An entry whose name ends like a seed keeps it when the seed differs.
  EXPECT_EQ(catalogPathForJob(libraryInputs("rock-s1-s2", 2, nullptr)), "rock-s1");
  // A plain bake: the preset's name, whatever its seed.
  EXPECT_EQ(catalogPathForJob({{"job", {{"name", "goblin"}, {"seed", 9}}}, {"library", nullptr}}), "goblin");
  // Nothing that would break the catalogue file's lines gets through.
  EXPECT_EQ(catalogPathForJob({{"job", {{"name", "a:b/c\nd"}}}, {"library", nullptr}}), "a-b-c-d");
  EXPECT_EQ(catalogPathForJob(json::object()), "rockbake");
}

TEST(BlenderCatalogs, UuidsAreDerivedFromThePathAlone) {
  const std::regex v8("[0-9a-f]{8}-[0-9a-f]{4}-8[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}");
  for (const std::string path : {"goblin", "goblin/tall", "rounded-cobble", "x"}) {
    EXPECT_TRUE(std::regex_match(catalogUuid(path), v8)) << catalogUuid(path);
    EXPECT_EQ(catalogUuid(path), catalogUuid(path));
  }
  EXPECT_NE(catalogUuid("goblin"), catalogUuid("goblin/tall"));
  // Pinned: a library re-made on another machine or by another version keeps its catalogues.
  EXPECT_EQ(catalogUuid("goblin"), blenderCatalog("goblin").uuid);
  EXPECT_EQ(blenderCatalog("goblin/tall").simple_name, "goblin-tall");
}

TEST(BlenderCatalogs, TheFileListsEveryCatalogueAndItsParentsOnceInBlendersFormat) {
  const auto catalogs = catalogsWithParents({"goblin/tall", "cobble", "goblin/soft", "cobble"});
  std::vector<std::string> paths;
  for (const auto& c : catalogs) paths.push_back(c.path);
  EXPECT_EQ(paths, (std::vector<std::string>{"cobble", "goblin", "goblin/soft", "goblin/tall"}));
  const std::string text = catalogFileText(catalogs);
  std::istringstream lines(text);
  std::string line;
  std::vector<std::string> content;
  while (std::getline(lines, line))
    if (!line.empty() && line[0] != '#') content.push_back(line);
  ASSERT_EQ(content.size(), 5u);
  EXPECT_EQ(content[0], "VERSION 1");
  EXPECT_EQ(content[2], catalogUuid("goblin") + ":goblin:goblin");
  EXPECT_EQ(content[4], catalogUuid("goblin/tall") + ":goblin/tall:goblin-tall");
  EXPECT_EQ(text, catalogFileText(catalogsWithParents({"cobble", "goblin/soft", "goblin/tall"})));
}

// A finished bake's files, as far as blender-library reads them (rock.glb's bytes are Blender's business).
void fakeAsset(const fs::path& dir, const std::string& name, bool in_library = true) {
  fs::create_directories(dir);
  const json inputs =
      in_library ? libraryInputs(name, 1, nullptr) : json{{"job", {{"name", name}}}, {"library", nullptr}};
  writeText(dir / "manifest.json", json{{"rockbake_manifest", 1}, {"asset", name}, {"inputs", inputs}}.dump());
  writeText(dir / "asset.json",
            json{{"rockbake_asset", 1},
                 {"name", name},
                 {"tags", {"sandstone", "hoodoo", "sandstone"}},
                 {"units_per_meter", 1.0},
                 {"size_m", {7.49148, 7.852381, 6.164977}},
                 {"lods",
                  {{{"level", 0}, {"file", "rock.glb"}, {"triangles", 4688}},
                   {{"level", 1}, {"file", "rock_lod1.glb"}, {"triangles", 1200}}}},
                 {"preview", "render.png"},
                 {"collision", {{"file", "collision.glb"}, {"naming", "unreal"}, {"hull_count", 13}}},
                 {"input_hash", "ab"}}
                .dump());
  for (const char* file : {"rock.glb", "rock_lod1.glb", "collision.glb", "render.png"}) writeText(dir / file, "x");
}

std::string inputErrorOf(const std::function<void()>& what) {
  try {
    what();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(BakedAssets, AFolderThatIsNotABakeIsRefusedByName) {
  TempDir tmp;
  const fs::path folder = tmp.path() / "photos";
  writeText(folder / "holiday.jpg", "x");
  const std::string message = inputErrorOf([&] { findBakedAssets({folder}); });
  EXPECT_NE(message.find(folder.string() + ": is not a rockbake bake"), std::string::npos) << message;
  EXPECT_NE(message.find("expected an asset folder (holding manifest.json"), std::string::npos) << message;
  EXPECT_NE(inputErrorOf([&] { findBakedAssets({tmp.path() / "nowhere"}); }).find("does not exist"), std::string::npos);
  EXPECT_NE(inputErrorOf([&] { findBakedAssets({folder / "holiday.jpg"}); }).find("is not a folder"),
            std::string::npos);
}

TEST(BakedAssets, AnAssetFolderMustBeAFinishedBakeWithAGlb) {
  TempDir tmp;
  fakeAsset(tmp.path() / "goblin-s1", "goblin-s1");
  const auto found = findBakedAssets({tmp.path() / "goblin-s1"});
  ASSERT_EQ(found.assets.size(), 1u);
  EXPECT_EQ(found.assets[0].name, "goblin-s1");
  EXPECT_EQ(found.assets[0].catalog, "goblin");
  EXPECT_EQ(found.assets[0].preview, "render.png");

  fs::remove(tmp.path() / "goblin-s1" / "render.png");  // no render: no preview, and that is fine
  EXPECT_EQ(findBakedAssets({tmp.path() / "goblin-s1"}).assets[0].preview, "");
  fs::remove(tmp.path() / "goblin-s1" / "rock_lod1.glb");
  EXPECT_NE(inputErrorOf([&] { findBakedAssets({tmp.path() / "goblin-s1"}); }).find("has no rock_lod1.glb"),
            std::string::npos);
  fs::remove(tmp.path() / "goblin-s1" / "asset.json");
  EXPECT_NE(inputErrorOf([&] { findBakedAssets({tmp.path() / "goblin-s1"}); }).find("without meshes"),
            std::string::npos);
  writeText(tmp.path() / "goblin-s1" / "manifest.json", "{\"rockbake_manifest\": 1, \"inp");
  EXPECT_NE(inputErrorOf([&] { findBakedAssets({tmp.path() / "goblin-s1"}); }).find("cut off or garbled"),
            std::string::npos);
}

TEST(BakedAssets, ALibrarySkipsWhatCannotBeDeliveredAndRefusesTwoAssetsOfOneName) {
  TempDir tmp;
  const fs::path out = tmp.path() / "out";
  fakeAsset(out / "goblin-s1", "goblin-s1");
  fakeAsset(out / "goblin-s2", "goblin-s2");
  writeText(out / "broken-s1" / "failure.json", "{}");
  fs::create_directories(out / ".goblin-s3.baking-12");
  const auto found = findBakedAssets({out});
  ASSERT_EQ(found.assets.size(), 2u);
  EXPECT_EQ(found.assets[1].name, "goblin-s2");
  ASSERT_EQ(found.skipped.size(), 1u);
  EXPECT_NE(found.skipped[0].find("broken-s1: skipped: a library job that failed"), std::string::npos);

  fakeAsset(tmp.path() / "loose" / "goblin-s2", "goblin-s2", false);
  EXPECT_NE(inputErrorOf([&] {
              findBakedAssets({out, tmp.path() / "loose" / "goblin-s2"});
            }).find("its asset 'goblin-s2' is also"),
            std::string::npos);
  fs::remove_all(out / "goblin-s1");
  fs::remove_all(out / "goblin-s2");
  EXPECT_NE(inputErrorOf([&] { findBakedAssets({out}); }).find("a library folder with no asset to deliver"),
            std::string::npos);
}

TEST(BlenderLibrary, OnlyANewAnEmptyOrRockbakesOwnFolderIsWritten) {
  TempDir tmp;
  EXPECT_FALSE(checkLibraryFolder(tmp.path() / "new").ours);
  fs::create_directories(tmp.path() / "empty");
  EXPECT_FALSE(checkLibraryFolder(tmp.path() / "empty").ours);
  writeText(tmp.path() / "file", "x");
  EXPECT_NE(inputErrorOf([&] { checkLibraryFolder(tmp.path() / "file"); }).find("is a file, not a folder"),
            std::string::npos);
  writeText(tmp.path() / "theirs" / "notes.txt", "x");
  EXPECT_NE(inputErrorOf([&] { checkLibraryFolder(tmp.path() / "theirs"); }).find("is a folder that is not"),
            std::string::npos);
  writeText(tmp.path() / "blender" / kBlenderCatalogFile, "VERSION 1\n");
  EXPECT_NE(inputErrorOf([&] {
              checkLibraryFolder(tmp.path() / "blender");
            }).find("is a Blender asset library rockbake did not write"),
            std::string::npos);
  writeText(tmp.path() / "ours" / kBlenderLibraryMarker,
            json{{"rockbake_blender_library", 1},
                 {"assets", {{{"file", "goblin-s1.blend"}}, {{"file", "../escape.blend"}}, {{"file", 3}}}}}
                .dump());
  const auto ours = checkLibraryFolder(tmp.path() / "ours");
  EXPECT_TRUE(ours.ours);
  EXPECT_EQ(ours.previous_files, std::vector<std::string>{"goblin-s1.blend"});
}

TEST(BlenderLibrary, TheDescriptionSaysWhatTheAssetIsAndItsSizeInMetres) {
  TempDir tmp;
  fakeAsset(tmp.path() / "goblin-s1", "goblin-s1");
  const auto asset = findBakedAssets({tmp.path() / "goblin-s1"}).assets[0];
  EXPECT_EQ(assetDescription(asset),
            "goblin-s1: a weathered rock baked by rockbake from the preset goblin, seed 7. 7.49 × 7.85 × 6.16 m "
            "(x × y × z, z up); LOD0 4,688 triangles. Its .blend also holds LOD1 and 13 collision hulls.");
  const json job = blenderJob(asset, blenderCatalog(asset.catalog), tmp.path() / "x.blend");
  EXPECT_EQ(job["tags"], json({"sandstone", "hoodoo"}));
  EXPECT_EQ(job["catalog"]["id"], catalogUuid("goblin"));
  EXPECT_EQ(job["author"], "rockbake");
  EXPECT_EQ(job["lods"].size(), 2u);
  EXPECT_EQ(job["preview"], "render.png");
}

// A stand-in for Blender: a script that prints `version` for --version.
fs::path fakeBlender(const fs::path& dir, const std::string& version) {
  const fs::path file = dir / "blender";
  writeText(file, "#!/bin/sh\necho '" + version + "'\n");
  chmod(file.c_str(), 0755);
  return file;
}

TEST(BlenderProgram, AMissingOrWrongBlenderIsRefusedWithWhatToInstall) {
  TempDir tmp;
  const std::string missing = inputErrorOf([&] { findBlender((tmp.path() / "no-blender").string()); });
  EXPECT_NE(missing.find("there is no such file"), std::string::npos) << missing;
  EXPECT_NE(missing.find("apt-get install blender"), std::string::npos) << missing;
  EXPECT_NE(missing.find("scripts/setup.sh"), std::string::npos) << missing;
  fs::create_directories(tmp.path() / "old");
  EXPECT_NE(inputErrorOf([&] {
              findBlender(fakeBlender(tmp.path() / "old", "Blender 2.93.1").string());
            }).find("is Blender 2.93.1; rockbake's Blender script needs 3.2 or newer"),
            std::string::npos);
  fs::create_directories(tmp.path() / "other");
  EXPECT_NE(inputErrorOf([&] {
              findBlender(fakeBlender(tmp.path() / "other", "GNU bash 5.2").string());
            }).find("is not Blender"),
            std::string::npos);
  fs::create_directories(tmp.path() / "good");
  const auto blender = findBlender(fakeBlender(tmp.path() / "good", "Blender 3.4.1\n\tbuild date: x").string());
  EXPECT_EQ(blender.version, "Blender 3.4.1");
  EXPECT_EQ(blender.major, 3);
  EXPECT_EQ(blender.minor, 4);
}

}  // namespace
}  // namespace rockbake
