// Sharing presets (docs/libraries.md, "Sharing presets"): installed catalogue presets by name
// (`extends: rockbake:NAME`), packs (`rockbake preset pack`, pack.json) and lint of a pack.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/sha256.h"
#include "preset/load_preset.h"
#include "preset/preset_files.h"
#include "preset/preset_json.h"
#include "preset/preset_pack.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::readBytes;
using test::runRockbake;
using test::runRockbakeUnder;
using test::TempDir;
using test::writeText;

fs::path catalogue(const std::string& name = "") {
  return fs::path(ROCKBAKE_SOURCE_DIR) / "presets" / name;
}

// Every file under `dir`, by its path relative to it.
std::set<std::string> filesUnder(const fs::path& dir) {
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (!entry.is_directory()) files.insert(entry.path().lexically_relative(dir).generic_string());
  return files;
}

// The 1-based line of `file` that starts with `start`, and "LINE:COLUMN" of the text after it.
int lineOf(const fs::path& file, const std::string& start) {
  const std::string text = readBytes(file);
  std::string needle(1, '\n');
  needle += start;
  const std::size_t at = text.find(needle);
  return at == std::string::npos ? 0 : int(std::count(text.begin(), text.begin() + at + 1, '\n')) + 1;
}
std::string placeAfter(const fs::path& file, const std::string& start) {
  return std::to_string(lineOf(file, start)) + ":" + std::to_string(start.size() + 1);
}

// Names in `dir` that a pack being written leaves behind (.<name>.packing-<pid>, .<name>.replaced-<pid>).
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().front() == '.') found.push_back(entry.path().filename().string());
  return found;
}

std::string packError(const std::vector<fs::path>& presets, const fs::path& out) {
  try {
    packPresets(presets, out);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// A small preset of its own beside a copy of goblin's image, extending the installed house style.
void writeOwnPreset(const fs::path& dir, const std::string& extends = "rockbake:base.yaml") {
  fs::create_directories(dir / "shapes");
  fs::copy_file(catalogue("shapes/goblin.png"), dir / "shapes" / "goblin.png");
  writeText(dir / "rock.yaml", "rockbake: 1\nextends: " + extends +
                                   "\nname: rock\nseed: 4\ngrid: {size: [3.0, 3.0, 3.0]}\nshape:\n"
                                   "  image: {path: shapes/goblin.png, mode: extrude, height: 2.0}\ntime: 0.4\n");
}

// ---- what a preset reaches ----

TEST(PresetFiles, ThePathKeysComeFromTheSchema) {
  const std::vector<std::string> keys = pathKeyPatterns();
  for (const char* key : {"shape.image.path", "shape.mesh.path"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key;
  EXPECT_EQ(std::find(keys.begin(), keys.end(), "extends"), keys.end());
  EXPECT_EQ(std::find(keys.begin(), keys.end(), "render.template"), keys.end()) << "a name, never a path";
}

TEST(PresetFiles, TheChainAndTheFilesItNamesWithTheirPlaces) {
  const PresetFiles files = presetFiles(catalogue("goblin.yaml"));
  ASSERT_EQ(files.chain.size(), 2u);
  EXPECT_EQ(files.chain[1].filename(), "base.yaml");
  ASSERT_EQ(files.refs.size(), 2u);
  EXPECT_EQ(files.refs[0].key_path, "extends");
  EXPECT_EQ(files.refs[0].written, "base.yaml");
  EXPECT_EQ(files.refs[0].where.line, lineOf(catalogue("goblin.yaml"), "extends: "));
  EXPECT_EQ(files.refs[1].key_path, "shape.image.path");
  EXPECT_EQ(files.refs[1].written, "shapes/goblin.png");
  EXPECT_EQ(files.refs[1].where.line, lineOf(catalogue("goblin.yaml"), "  image: {path: "));
  EXPECT_EQ(files.refs[1].target, catalogue("shapes/goblin.png").lexically_normal());
  // A blockout, through its own key.
  const PresetFiles boulder = presetFiles(catalogue("boulder-blockout.yaml"));
  ASSERT_EQ(boulder.refs.size(), 2u);
  EXPECT_EQ(boulder.refs[1].key_path, "shape.mesh.path");
}

// ---- installed catalogue presets by name ----

TEST(CatalogueExtends, ANameResolvesInTheDataFolder) {
  TempDir dir;
  writeOwnPreset(dir.path());
  const Preset own = loadPreset(dir.path() / "rock.yaml");
  EXPECT_EQ(own.grid.resolution, 96);  // the house style's
  ASSERT_EQ(own.sources.size(), 2u);
  EXPECT_EQ(fs::weakly_canonical(own.sources[1]), fs::weakly_canonical(catalogue("base.yaml")));

  // ROCKBAKE_DATA_DIR chooses the folder: a house style only that folder has.
  const fs::path data = dir.path() / "data";
  fs::create_directories(data / "presets");
  fs::create_directory_symlink(fs::path(ROCKBAKE_SOURCE_DIR) / "render_templates", data / "render_templates");
  writeText(data / "presets" / "house.yaml", "rockbake: 1\ngrid: {resolution: 20}\ncolluvium: {yield: 0.25}\n");
  writeOwnPreset(dir.path() / "studio", "rockbake:house.yaml");
  const std::string preset = (dir.path() / "studio" / "rock.yaml").string();
  const auto shown = runRockbakeUnder("ROCKBAKE_DATA_DIR=" + data.string() + " ", {"preset", "show", preset});
  ASSERT_EQ(shown.exit_status, 0) << shown.output;
  EXPECT_NE(shown.output.find("\"resolution\": 20"), std::string::npos) << shown.output;
  const auto elsewhere = runRockbake({"lint", preset});
  EXPECT_EQ(elsewhere.exit_status, 2) << elsewhere.output;
  EXPECT_NE(elsewhere.output.find("rock.yaml:2:10: extends: no installed catalogue preset 'house.yaml'"),
            std::string::npos)
      << elsewhere.output;
}

TEST(CatalogueExtends, BadNamesAreRefusedAtTheExtends) {
  TempDir dir;
  for (const auto& [name, expected] : std::vector<std::pair<std::string, std::string>>{
           {"rockbake:bsae.yaml", "no installed catalogue preset 'bsae.yaml'"},
           {"rockbake:../../etc/base.yaml", "it may not hold '.' or '..'"},
           {"rockbake:/etc/base.yaml", "it is an absolute path"},
           {"'rockbake:'", "nothing after 'rockbake:'"}}) {
    writeText(dir.path() / "p.yaml", "rockbake: 1\nextends: " + name + "\nname: p\n");
    try {
      loadPreset(dir.path() / "p.yaml");
      ADD_FAILURE() << name << " loaded";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().line, 2) << e.what();
      EXPECT_EQ(e.keyPath(), "extends");
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  writeText(dir.path() / "p.yaml", "rockbake: 1\nextends: rockbake:bsae.yaml\nname: p\n");
  const auto lint = runRockbake({"lint", (dir.path() / "p.yaml").string()});
  EXPECT_NE(lint.output.find("did you mean rockbake:base.yaml?"), std::string::npos) << lint.output;
}

// ---- packs ----

// Goblin (an image shape and a base) packed, the pack moved to an empty folder elsewhere, both baked: every
// asset file is the same bytes. manifest.json differs only in its timings, host and stats.json's entry, and
// stats.json in its stage seconds and the image path its preset records absolute (docs/formats.md).
TEST(PresetPack, AMovedPackBakesWhatTheOriginalBakes) {
  TempDir dir;
  const auto packed = runRockbake({"preset", "pack", catalogue("goblin.yaml").string(), "-o",
                                   (dir.path() / "made" / "goblin-pack").string()});
  ASSERT_EQ(packed.exit_status, 0) << packed.output;
  const fs::path pack = dir.path() / "elsewhere" / "moved";
  fs::create_directories(pack.parent_path());
  fs::rename(dir.path() / "made" / "goblin-pack", pack);
  EXPECT_EQ(filesUnder(pack),
            (std::set<std::string>{"pack.json", "goblin.yaml", "base.yaml", "shapes/goblin.png"}));
  for (const char* file : {"goblin.yaml", "base.yaml", "shapes/goblin.png"})
    EXPECT_EQ(readBytes(pack / file), readBytes(catalogue(file))) << file << ": copied as it is";

  const std::vector<std::string> fast = {"--resolution", "32", "--no-render", "--set", "texture.size=256"};
  std::map<std::string, fs::path> out;
  for (const auto& [name, preset] : std::map<std::string, fs::path>{{"original", catalogue("goblin.yaml")},
                                                                     {"pack", pack / "goblin.yaml"}}) {
    std::vector<std::string> args = {"bake", preset.string(), "-o", (dir.path() / name).string()};
    args.insert(args.end(), fast.begin(), fast.end());
    const auto baked = runRockbake(args);
    ASSERT_EQ(baked.exit_status, 0) << baked.output;
    out[name] = dir.path() / name / "goblin";
  }
  const std::set<std::string> files = filesUnder(out["original"]);
  ASSERT_EQ(files, filesUnder(out["pack"]));
  ASSERT_TRUE(files.count("rock.glb") && files.count("rock.vdb") && files.count("asset.json") &&
              files.count("textures/goblin_BaseColor.png"));
  for (const auto& file : files) {
    if (file == "manifest.json" || file == "stats.json") continue;
    EXPECT_TRUE(readBytes(out["original"] / file) == readBytes(out["pack"] / file)) << file << " differs";
  }
  std::map<std::string, json> manifests, stats;
  for (const auto& [name, asset] : out) {
    json manifest = json::parse(readBytes(asset / "manifest.json"));
    manifest.erase("timings");
    manifest.erase("host");
    json& outputs = manifest["outputs"];
    outputs.erase(std::remove_if(outputs.begin(), outputs.end(), [](const json& o) { return o["path"] == "stats.json"; }),
                  outputs.end());
    manifests[name] = manifest;
    json s = json::parse(readBytes(asset / "stats.json"));
    s.erase("stages");
    const fs::path image = s["preset"]["shape"]["image"]["path"].get<std::string>();
    s["preset"]["shape"]["image"]["path"] = image.lexically_relative(image.parent_path().parent_path()).string();
    stats[name] = s;
  }
  EXPECT_EQ(manifests["original"], manifests["pack"]);
  EXPECT_EQ(stats["original"], stats["pack"]);
}

TEST(PresetPack, PackJsonListsEveryFileWithItsHash) {
  TempDir dir;
  const PackSummary summary = packPresets({catalogue("boulder-blockout.yaml")}, dir.path() / "pack");
  EXPECT_EQ(summary.files, 3u);
  EXPECT_FALSE(summary.replaced);
  const json manifest = json::parse(readBytes(dir.path() / "pack" / "pack.json"));
  EXPECT_EQ(manifest["rockbake_pack"], 1);
  EXPECT_EQ(manifest["rockbake_version"], ROCKBAKE_VERSION);
  EXPECT_EQ(manifest["presets"], json::array({"boulder-blockout.yaml"}));
  std::vector<std::string> paths;
  for (const auto& file : manifest["files"]) {
    paths.push_back(file["path"]);
    const fs::path copy = dir.path() / "pack" / file["path"].get<std::string>();
    EXPECT_EQ(file["size"], fs::file_size(copy));
    EXPECT_EQ(file["sha256"], sha256File(copy));
  }
  EXPECT_EQ(paths, (std::vector<std::string>{"base.yaml", "boulder-blockout.yaml", "shapes/boulder.obj"}));
  EXPECT_EQ(manifest["files"][2]["role"], "shape.mesh.path");
  // Packing again gives the same pack.json: no dates in it.
  packPresets({catalogue("boulder-blockout.yaml")}, dir.path() / "again");
  EXPECT_EQ(readBytes(dir.path() / "pack" / "pack.json"), readBytes(dir.path() / "again" / "pack.json"));
}

// A preset extending an installed catalogue preset: the base is copied into the pack's rockbake/ and the
// extends rewritten to name the copy, so the pack bakes without the installed catalogue.
TEST(PresetPack, AnInstalledBaseIsCopiedIntoThePack) {
  TempDir dir;
  writeOwnPreset(dir.path() / "mine");
  writeText(dir.path() / "mine" / "inherits.yaml", "rockbake: 1\nextends: 'rockbake:goblin.yaml'\nname: inherits\n");
  const auto packed = runRockbake({"preset", "pack", (dir.path() / "mine" / "rock.yaml").string(),
                                   (dir.path() / "mine" / "inherits.yaml").string(), "-o",
                                   (dir.path() / "pack").string()});
  ASSERT_EQ(packed.exit_status, 0) << packed.output;
  const fs::path pack = dir.path() / "pack";
  EXPECT_EQ(filesUnder(pack), (std::set<std::string>{"pack.json", "rock.yaml", "inherits.yaml", "shapes/goblin.png",
                                                     "rockbake/base.yaml", "rockbake/goblin.yaml",
                                                     "rockbake/shapes/goblin.png"}));
  std::string expected = readBytes(dir.path() / "mine" / "rock.yaml");
  expected.replace(expected.find("rockbake:base.yaml"), 18, "rockbake/base.yaml");
  EXPECT_EQ(readBytes(pack / "rock.yaml"), expected);
  EXPECT_NE(readBytes(pack / "inherits.yaml").find("extends: rockbake/goblin.yaml\n"), std::string::npos);
  EXPECT_EQ(readBytes(pack / "rockbake" / "goblin.yaml"), readBytes(catalogue("goblin.yaml")));
  const json manifest = json::parse(readBytes(pack / "pack.json"));
  std::map<std::string, std::string> from;
  for (const auto& file : manifest["files"]) from[file["path"]] = file.value("catalogue", "");
  EXPECT_EQ(from["rockbake/base.yaml"], "rockbake:base.yaml");
  EXPECT_EQ(from["rockbake/shapes/goblin.png"], "rockbake:shapes/goblin.png");
  EXPECT_EQ(from["rock.yaml"], "");

  // Moved, with no catalogue to be found (ROCKBAKE_DATA_DIR names a data folder without presets/), it
  // bakes the same rock.
  fs::rename(pack, dir.path() / "moved");
  fs::create_directories(dir.path() / "no-data");
  fs::create_directory_symlink(fs::path(ROCKBAKE_SOURCE_DIR) / "render_templates",
                               dir.path() / "no-data" / "render_templates");
  const std::string no_data = "ROCKBAKE_DATA_DIR=" + (dir.path() / "no-data").string() + " ";
  for (const auto& [preset, out] : std::vector<std::pair<fs::path, std::string>>{
           {dir.path() / "mine" / "rock.yaml", "a"}, {dir.path() / "moved" / "rock.yaml", "b"}}) {
    const auto baked = runRockbakeUnder(out == "b" ? no_data : "", {"bake", preset.string(), "--resolution", "24",
                                                                    "--no-render", "--no-textures", "-o",
                                                                    (dir.path() / out).string()});
    ASSERT_EQ(baked.exit_status, 0) << baked.output;
  }
  for (const char* file : {"rock.glb", "rock.vdb", "rock.ply", "collision.glb", "asset.json"})
    EXPECT_TRUE(readBytes(dir.path() / "a" / "rock" / file) == readBytes(dir.path() / "b" / "rock" / file)) << file;
}

// An absolute path to a file of the preset's own folder is shared as a relative one.
TEST(PresetPack, AbsolutePathsInsideTheFolderBecomeRelative) {
  TempDir dir;
  const std::string house = (dir.path() / "mine" / "house.yaml").string();
  writeOwnPreset(dir.path() / "mine", std::string(1, '\'').append(house).append(1, '\''));
  writeText(dir.path() / "mine" / "house.yaml", "rockbake: 1\ngrid: {resolution: 20}\n");
  std::string text = readBytes(dir.path() / "mine" / "rock.yaml");
  text.replace(text.find("shapes/goblin.png"), 17, (dir.path() / "mine" / "shapes" / "goblin.png").string());
  writeText(dir.path() / "mine" / "rock.yaml", text);
  const PackSummary summary = packPresets({dir.path() / "mine" / "rock.yaml"}, dir.path() / "pack");
  EXPECT_EQ(summary.rewritten, 2u);
  const std::string packed = readBytes(dir.path() / "pack" / "rock.yaml");
  EXPECT_NE(packed.find("extends: house.yaml\n"), std::string::npos) << packed;
  EXPECT_NE(packed.find("image: {path: shapes/goblin.png, mode"), std::string::npos) << packed;
  EXPECT_EQ(loadPreset(dir.path() / "pack" / "rock.yaml").grid.resolution, 20);
}

// Only the value changes: a byte order mark, CRLF line ends, non-ASCII comments and quoting stay as written.
TEST(PresetPack, ARewriteChangesTheValueAlone) {
  TempDir dir;
  const std::string head = "\xEF\xBB\xBF# caf\xC3\xA9 \xE2\x80\x94 a rock\r\nrockbake: 1\r\nextends: ";
  const std::string tail = "   # the house style\r\nname: r\r\nshape: {box: {size: [1, 1, 1]}}\r\ntime: 0.5\r\n";
  for (const std::string written : {"rockbake:base.yaml", "'rockbake:base.yaml'", "\"rockbake:base.yaml\""}) {
    writeText(dir.path() / "mine" / "r.yaml", head + written + tail);
    packPresets({dir.path() / "mine" / "r.yaml"}, dir.path() / "pack");
    EXPECT_EQ(readBytes(dir.path() / "pack" / "r.yaml"), head + "rockbake/base.yaml" + tail) << written;
    EXPECT_TRUE(checkPack(dir.path() / "pack").problems.empty()) << written;
  }
}

TEST(PresetPack, AnExistingPackIsReplacedWhole) {
  TempDir dir;
  writeOwnPreset(dir.path() / "mine", "rockbake:base.yaml");
  const fs::path pack = dir.path() / "pack";
  packPresets({catalogue("goblin.yaml")}, pack);
  writeText(dir.path() / ".pack.packing-999999" / "goblin.yaml", "left by a pack that was killed\n");
  const PackSummary again = packPresets({dir.path() / "mine" / "rock.yaml"}, pack);
  EXPECT_TRUE(again.replaced);
  EXPECT_EQ(filesUnder(pack), (std::set<std::string>{"pack.json", "rock.yaml", "shapes/goblin.png",
                                                     "rockbake/base.yaml"}));
  EXPECT_TRUE(leftovers(dir.path()).empty());
  // An empty folder is taken too: there is nothing in it to lose.
  fs::create_directory(dir.path() / "empty");
  EXPECT_FALSE(packPresets({catalogue("goblin.yaml")}, dir.path() / "empty").replaced);
  EXPECT_TRUE(fs::exists(dir.path() / "empty" / "pack.json"));
}

// Each bad input: exit status 2, file:line:col: key.path and what to do, nothing written or overwritten.
TEST(PresetPack, BadInputWritesNothing) {
  TempDir dir;
  const fs::path mine = dir.path() / "mine";
  writeOwnPreset(mine);
  fs::create_directories(dir.path() / "shared");
  fs::copy_file(catalogue("shapes/mesa.png"), dir.path() / "shared" / "mesa.png");
  fs::copy_file(catalogue("base.yaml"), dir.path() / "shared" / "house.yaml");
  const std::string own = readBytes(mine / "rock.yaml");
  const auto variant = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string text = own;
    text.replace(text.find(from), from.size(), to);
    writeText(mine / name, text);
    return mine / name;
  };
  fs::create_directory_symlink("../../shared", mine / "shapes" / "linked");
  const std::vector<std::tuple<fs::path, std::string>> cases = {
      {variant("outside.yaml", "shapes/goblin.png", "../shared/mesa.png"),
       "outside.yaml:7:17: shape.image.path: '../shared/mesa.png' reaches outside the preset's folder"},
      {variant("absolute.yaml", "shapes/goblin.png", (dir.path() / "shared" / "mesa.png").string()),
       "absolute.yaml:7:17: shape.image.path: '" + (dir.path() / "shared" / "mesa.png").string() +
           "' reaches outside"},
      {variant("link.yaml", "shapes/goblin.png", "shapes/linked/mesa.png"),
       "link.yaml:7:17: shape.image.path: 'shapes/linked/mesa.png' reaches outside the preset's folder"},
      {variant("extends-outside.yaml", "rockbake:base.yaml", "../shared/house.yaml"),
       "extends-outside.yaml:2:10: extends: '../shared/house.yaml' reaches outside the preset's folder"},
      {variant("missing.yaml", "shapes/goblin.png", "shapes/nothing.png"),
       "missing.yaml:7:17: shape.image.path: no image file at"},
  };
  for (const auto& [preset, expected] : cases) {
    const auto result = runRockbake({"preset", "pack", preset.string(), "-o", (dir.path() / "out" / "pack").string()});
    EXPECT_EQ(result.exit_status, 2) << result.output;
    EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
    EXPECT_NE(result.output.find(" ("), std::string::npos) << "says what to do: " << result.output;
    EXPECT_FALSE(fs::exists(dir.path() / "out")) << preset;
  }
  EXPECT_EQ(leftovers(dir.path()), std::vector<std::string>{});

  // A target that is not a pack is never overwritten.
  fs::create_directories(dir.path() / "work");
  writeText(dir.path() / "work" / "notes.txt", "mine\n");
  writeText(dir.path() / "file", "a file\n");
  fs::create_directory_symlink("work", dir.path() / "link");
  for (const auto& [target, expected] : std::vector<std::pair<std::string, std::string>>{
           {"work", "work: is a folder that is not a pack (it holds no pack.json)"},
           {"file", "file: is a file, not a pack folder"},
           {"link", "link: is a symbolic link, not a pack"}}) {
    const auto result =
        runRockbake({"preset", "pack", (mine / "rock.yaml").string(), "-o", (dir.path() / target).string()});
    EXPECT_EQ(result.exit_status, 2) << result.output;
    EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("give -o a new folder"), std::string::npos) << result.output;
  }
  EXPECT_EQ(filesUnder(dir.path() / "work"), std::set<std::string>{"notes.txt"});
  EXPECT_EQ(readBytes(dir.path() / "file"), "a file\n");
  EXPECT_EQ(leftovers(dir.path()), std::vector<std::string>{});
  // Presets of two folders: one pack holds one folder's.
  EXPECT_NE(packError({mine / "rock.yaml", catalogue("goblin.yaml")}, dir.path() / "two").find("is not in"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir.path() / "two"));
}

// ---- lint of a pack ----

TEST(PackLint, AGoodPackIsOk) {
  TempDir dir;
  packPresets({catalogue("goblin.yaml")}, dir.path() / "pack");
  const auto lint = runRockbake({"lint", (dir.path() / "pack").string()});
  EXPECT_EQ(lint.exit_status, 0) << lint.output;
  EXPECT_NE(lint.output.find("pack: ok (a pack of 1 preset and 3 files, every file's SHA-256 checked)"),
            std::string::npos)
      << lint.output;
  const auto one = runRockbake({"lint", (dir.path() / "pack" / "goblin.yaml").string()});
  EXPECT_EQ(one.exit_status, 0) << one.output;
  EXPECT_NE(one.output.find("goblin.yaml: ok (in a pack: its pack.json checked too)"), std::string::npos)
      << one.output;
  EXPECT_TRUE(checkPack(dir.path() / "pack").problems.empty());
}

TEST(PackLint, ATamperedPackSaysWhatChanged) {
  TempDir dir;
  const fs::path pack = dir.path() / "pack";
  packPresets({catalogue("goblin.yaml")}, pack);
  std::string image = readBytes(pack / "shapes" / "goblin.png");
  image[image.size() - 20] ^= 1;  // the same size, other bytes
  writeText(pack / "shapes" / "goblin.png", image);
  writeText(pack / "notes.txt", "added\n");
  fs::remove(pack / "base.yaml");
  fs::create_directories(dir.path() / "shared");
  fs::copy_file(catalogue("base.yaml"), dir.path() / "shared" / "base.yaml");
  fs::create_symlink("../shared/base.yaml", pack / "house.yaml");
  const auto lint = runRockbake({"lint", pack.string()});
  EXPECT_EQ(lint.exit_status, 2) << lint.output;
  std::string extends_at = "goblin.yaml:";
  extends_at.append(placeAfter(catalogue("goblin.yaml"), "extends: ")).append(": extends: ");
  for (const std::string expected :
       {std::string("pack/shapes/goblin.png: does not match its SHA-256 in pack.json (files.2.sha256)"),
        std::string("pack/base.yaml: is missing; pack.json lists base.yaml (files.0)"),
        std::string("pack/notes.txt: is not listed in pack.json"), std::string("pack/house.yaml: is a symbolic link"),
        extends_at + "no base preset at"})
    EXPECT_NE(lint.output.find(expected), std::string::npos) << expected << "\n" << lint.output;

  // A preset edited to reach outside the pack.
  fs::remove(pack / "house.yaml");
  fs::copy_file(dir.path() / "shared" / "base.yaml", pack / "base.yaml");
  std::string preset = readBytes(pack / "goblin.yaml");
  preset.replace(preset.find("extends: base.yaml"), 18, "extends: ../shared/base.yaml");
  writeText(pack / "goblin.yaml", preset);
  const auto outside = runRockbake({"lint", (pack / "goblin.yaml").string()});
  EXPECT_EQ(outside.exit_status, 2) << outside.output;
  EXPECT_NE(outside.output.find(extends_at + "'../shared/base.yaml' reaches outside the pack"), std::string::npos)
      << outside.output;
  const std::uintmax_t size = fs::file_size(catalogue("goblin.yaml"));
  EXPECT_NE(outside.output.find("goblin.yaml: is " + std::to_string(size + 10) + " bytes; pack.json (files.1.size) says " +
                                std::to_string(size)),
            std::string::npos)
      << outside.output;

  // A folder that is no pack, and a pack.json that is not one.
  const auto none = runRockbake({"lint", dir.path().string()});
  EXPECT_EQ(none.exit_status, 2);
  EXPECT_NE(none.output.find("is not a pack: it holds no pack.json"), std::string::npos) << none.output;
  writeText(pack / "pack.json", "{\"rockbake_pack\": 2, \"files\": [], \"presets\": [\"goblin.yaml\"]}\n");
  const auto future = runRockbake({"lint", pack.string()});
  EXPECT_NE(future.output.find("pack.json: rockbake_pack: pack format 2 is not supported"), std::string::npos)
      << future.output;
}

}  // namespace
}  // namespace rockbake
