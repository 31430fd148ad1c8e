// Render stage (docs/rendering.md): real POV-Ray renders at thumbnail size, read back
// with OpenEXR; OpenColorIO against the sRGB formula; failure messages.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <regex>
#include <string>
#include <utility>

#include "render/exr_metadata.h"
#include "render/povray.h"
#include "render/preview.h"
#include "render/render_asset.h"
#include "render/scene.h"
#include "exr_image.h"
#include "test_support.h"

namespace rockbake {
namespace {

using Color = std::array<float, 3>;
using Pos = std::array<float, 3>;

// A subdivided icosphere about `c`, coloured per vertex by `color(position)`.
SurfaceMesh icosphere(int levels, Pos c, float r, const std::function<Color(const Pos&)>& color) {
  const TriangleMesh sphere = test::icosphere(levels);
  SurfaceMesh m;
  m.name = "rock";
  for (const auto& d : sphere.positions) {
    const Pos n{float(d[0]), float(d[1]), float(d[2])};
    const Pos p{c[0] + r * n[0], c[1] + r * n[1], c[2] + r * n[2]};
    m.positions.push_back(p);
    m.normals.push_back(n);
    m.colors.push_back(color(p));
  }
  m.triangles = sphere.triangles;
  return m;
}

AssetMeshes asset(SurfaceMesh rock) {
  AssetMeshes a;
  a.rock = std::move(rock);
  a.bounds_min = {1e30f, 1e30f, 1e30f};
  a.bounds_max = {-1e30f, -1e30f, -1e30f};
  for (const auto& p : a.rock.positions)
    for (int i = 0; i < 3; ++i) {
      a.bounds_min[i] = std::min(a.bounds_min[i], p[i]);
      a.bounds_max[i] = std::max(a.bounds_max[i], p[i]);
    }
  return a;
}

// Red above z = 1, blue below: a sphere of radius 1 resting on the ground.
AssetMeshes twoLayerRock(int levels = 3) {
  return asset(icosphere(levels, {0, 0, 1}, 1.0f, [](const Pos& p) {
    return p[2] > 1.0f ? Color{1.0f, 0.0f, 0.0f} : Color{0.0f, 0.0f, 1.0f};
  }));
}

RenderRequest request(const std::filesystem::path& dir, const std::string& tmpl, int w, int h, int frames = 0) {
  RenderRequest r;
  r.asset_dir = dir;
  r.params.template_name = tmpl;
  r.params.width = w;
  r.params.height = h;
  r.params.quality = 9;
  r.params.antialias = 0;  // exact colours, faster
  r.params.turntable_frames = frames;
  r.preset_name = "test_rock";
  r.seed = 18446744073709551615ull;
  r.preset_hash = "abc123";
  r.threads = 2;
  r.timeout = std::chrono::seconds(60);
  return r;
}

using test::ExrImage;
using test::readExr;

std::string stringAttr(const Imf::Header& h, const char* name) {
  const auto* a = h.findTypedAttribute<Imf::StringAttribute>(name);
  return a ? a->value() : "<missing>";
}

TEST(RenderTest, StillIsHalfEXRWithMetadataAndFramedAsset) {
  test::TempDir dir;
  const RenderOutputs out = renderAsset(twoLayerRock(), request(dir.path(), "debug", 64, 48));
  ASSERT_TRUE(std::filesystem::is_regular_file(out.render_exr));
  EXPECT_TRUE(std::filesystem::is_regular_file(out.render_png));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "scene.pov"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "rock_mesh.inc"));

  Imf::InputFile file(out.render_exr.string().c_str());
  const Imf::Header& h = file.header();
  for (const char* c : {"R", "G", "B"}) {
    const Imf::Channel* ch = h.channels().findChannel(c);
    ASSERT_NE(ch, nullptr) << c;
    EXPECT_EQ(ch->type, Imf::HALF) << c;
  }
  EXPECT_EQ(stringAttr(h, "rockbake:preset"), "test_rock");
  EXPECT_EQ(stringAttr(h, "rockbake:seed"), "18446744073709551615");
  EXPECT_EQ(stringAttr(h, "rockbake:preset_hash"), "abc123");
  EXPECT_EQ(stringAttr(h, "rockbake:version"), ROCKBAKE_VERSION);
  EXPECT_NE(stringAttr(h, "rockbake:camera").find("look_at 0 0 1"), std::string::npos)
      << stringAttr(h, "rockbake:camera");
  const auto* frame = h.findTypedAttribute<Imf::FloatAttribute>("rockbake:frame");
  ASSERT_NE(frame, nullptr);
  EXPECT_EQ(frame->value(), 0.0f);

  // The debug template's background is black; the asset is everything else.
  const ExrImage img = readExr(out.render_exr);
  ASSERT_EQ(img.width, 64);
  ASSERT_EQ(img.height, 48);
  double n = 0, sx = 0, sy = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (img.at("R", x, y) + img.at("G", x, y) + img.at("B", x, y) > 0.02f) n += 1, sx += x + 0.5, sy += y + 0.5;
    }
  const double coverage = n / (img.width * img.height);
  EXPECT_GT(coverage, 0.15);
  EXPECT_LT(coverage, 0.85);
  ASSERT_GT(n, 0);
  EXPECT_NEAR(sx / n, img.width / 2.0, 0.1 * img.width);
  EXPECT_NEAR(sy / n, img.height / 2.0, 0.1 * img.height);
}

TEST(RenderTest, FramingFillsTallAndWideImages) {
  // A wide, flat slab and a tall column, each in a wide and a tall image: the
  // asset spans most of the frame in one direction and is never cut off.
  for (const auto& [sx, sz] : {std::pair{3.0f, 0.5f}, std::pair{0.5f, 3.0f}}) {
    SurfaceMesh m = icosphere(2, {0, 0, 0}, 1.0f, [](const Pos&) { return Color{1, 1, 1}; });
    for (auto& p : m.positions) p = {p[0] * sx, p[1] * sx, p[2] * sz + sz};
    const AssetMeshes a = asset(m);
    for (const auto& [w, h] : {std::pair{64, 32}, std::pair{32, 64}}) {
      test::TempDir dir;
      const RenderOutputs out = renderAsset(a, request(dir.path(), "debug", w, h));
      const ExrImage img = readExr(out.render_exr);
      int border = 0, x0 = w, x1 = -1, y0 = h, y1 = -1;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          if (img.at("R", x, y) > 0.02f) {
            x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            if (x == 0 || y == 0 || x == w - 1 || y == h - 1) ++border;
          }
      const double fill = std::max(double(x1 - x0 + 1) / w, double(y1 - y0 + 1) / h);
      EXPECT_GT(fill, 0.5) << sx << "x" << sz << " in " << w << "x" << h;
      EXPECT_EQ(border, 0) << sx << "x" << sz << " in " << w << "x" << h;
    }
  }
}

TEST(RenderTest, DebugColoursSurvive) {
  test::TempDir dir;
  const RenderOutputs out = renderAsset(twoLayerRock(), request(dir.path(), "debug", 64, 48));
  const ExrImage img = readExr(out.render_exr);
  // The sphere fills the image height about its centre; the camera is 20°
  // above the horizon, so the red (upper) half is above the image centre.
  const int top = 24 - 12, bottom = 24 + 12;
  EXPECT_GT(img.at("R", 32, top), 0.9f);
  EXPECT_LT(img.at("B", 32, top), 0.05f);
  EXPECT_LT(img.at("R", 32, bottom), 0.05f);
  EXPECT_GT(img.at("B", 32, bottom), 0.9f);
  EXPECT_LT(img.at("G", 32, top) + img.at("G", 32, bottom), 0.05f);
}

double srgbEncode(double v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

TEST(RenderTest, OcioDisplayMatchesSrgbFormula) {
  for (double v : {0.0, 0.001, 0.0031308, 0.01, 0.05, 0.18, 0.5, 0.75, 1.0}) {
    const auto d = sceneLinearToDisplay({float(v), float(v) * 0.5f, float(v) * 0.25f});
    EXPECT_NEAR(d[0], srgbEncode(v), 1e-3) << v;
    EXPECT_NEAR(d[1], srgbEncode(v * 0.5), 1e-3) << v;
    EXPECT_NEAR(d[2], srgbEncode(v * 0.25), 1e-3) << v;
    const auto back = srgbToSceneLinear({float(srgbEncode(v)), 0.5f, 1.0f});
    EXPECT_NEAR(back[0], v, 1e-4) << v;
    EXPECT_NEAR(back[1], std::pow((0.5 + 0.055) / 1.055, 2.4), 1e-4);
    EXPECT_NEAR(back[2], 1.0, 1e-4);
  }
}

TEST(RenderTest, ShippedOcioConfigPassesOciocheck) {
  const std::string cmd = "ociocheck --iconfig '" + defaultOcioConfig().string() + "' 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string output;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) output.append(buf, n);
  const int status = pclose(p);
  ASSERT_EQ(status, 0) << output;
  EXPECT_EQ(output.find("ERROR"), std::string::npos) << output;
  EXPECT_NE(output.find("passed"), std::string::npos) << output;
}

TEST(RenderTest, TurntableFramesDifferAndContactSheetHasGridSize) {
  test::TempDir dir;
  // Asymmetric colours, so every view differs.
  const AssetMeshes a = asset(icosphere(2, {0, 0, 1}, 1.0f, [](const Pos& p) {
    return Color{p[0] > 0 ? 0.8f : 0.1f, p[1] > 0 ? 0.6f : 0.1f, 0.2f};
  }));
  const RenderOutputs out = renderAsset(a, request(dir.path(), "studio", 40, 30, 3));
  ASSERT_EQ(out.turntable_frames.size(), 3u);
  std::vector<ExrImage> frames;
  for (int i = 0; i < 3; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "turntable/%04d.exr", i);
    EXPECT_EQ(out.turntable_frames[std::size_t(i)], dir.path() / name);
    ASSERT_TRUE(std::filesystem::is_regular_file(dir.path() / name)) << name;
    frames.push_back(readExr(dir.path() / name));
    Imf::InputFile f((dir.path() / name).string().c_str());
    EXPECT_EQ(f.header().findTypedAttribute<Imf::FloatAttribute>("rockbake:frame")->value(), float(i));
  }
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      const ExrImage &fi = frames[std::size_t(i)], &fj = frames[std::size_t(j)];
      double diff = 0;
      for (std::size_t k = 0; k < frames[0].plane("R").size(); ++k)
        diff += std::abs(fi.plane("R")[k] - fj.plane("R")[k]) + std::abs(fi.plane("G")[k] - fj.plane("G")[k]);
      EXPECT_GT(diff / double(frames[0].plane("R").size()), 1e-3) << i << " vs " << j;
    }
  // 3 frames → 2 × 2 grid of 40 × 30.
  const ExrImage sheet = readExr(out.turntable_sheet_exr);
  EXPECT_EQ(sheet.width, 80);
  EXPECT_EQ(sheet.height, 60);
  EXPECT_FLOAT_EQ(sheet.at("R", 39, 29), frames[0].at("R", 39, 29));
  EXPECT_FLOAT_EQ(sheet.at("G", 40 + 5, 7), frames[1].at("G", 5, 7));
  EXPECT_TRUE(std::filesystem::is_regular_file(out.turntable_sheet_png));
  EXPECT_TRUE(std::filesystem::is_regular_file(out.render_png));
}

TEST(RenderTest, TemplateSyntaxErrorSurfacesPovrayMessage) {
  test::TempDir dir;
  const auto templates = dir.path() / "templates";
  test::writeText(templates / "broken.pov",
                  "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n#include \"{{MESH_INCLUDE}}\"\n"
                  "camera { location {{CAMERA_LOCATION}} look_at {{CAMERA_LOOK_AT}} }\n"
                  "object { Rockbake_Rock pigment { rgb 1 }\n");  // missing brace
  RenderRequest r = request(dir.path() / "asset", "broken", 32, 24);
  r.template_dir = templates;
  try {
    renderAsset(twoLayerRock(1), r);
    FAIL() << "expected a POV-Ray error";
  } catch (const PovrayError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("Parse Error"), std::string::npos) << what;
    EXPECT_NE(what.find("scene.pov"), std::string::npos) << what;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "asset" / "render.exr"));
}

TEST(RenderTest, UnknownPlaceholderAndMissingTemplateAreClearErrors) {
  EXPECT_THROW(
      {
        try {
          fillTemplate("a\n{{CAMERA_LOCATOIN}}", {{"CAMERA_LOCATION", "<0,0,0>"}}, "t.pov");
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("t.pov:2: unknown placeholder {{CAMERA_LOCATOIN}}"), std::string::npos)
              << e.what();
          throw;
        }
      },
      std::runtime_error);
  try {
    findTemplate(defaultRenderTemplatesDir(), "no_such_template");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("studio"), std::string::npos) << e.what();
  }
}

TEST(RenderTest, MissingPovrayNamesThePackage) {
  test::TempDir dir;
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  setenv("PATH", dir.path().string().c_str(), 1);
  std::string what;
  try {
    renderAsset(twoLayerRock(1), request(dir.path() / "asset", "debug", 32, 24));
  } catch (const PovrayError& e) {
    what = e.what();
  }
  setenv("PATH", saved.c_str(), 1);
  EXPECT_NE(what.find("apt-get install povray"), std::string::npos) << what;
}

// A lone still uses the cores: with two threads, two single-threaded POV-Ray processes render
// its two bands of whole blocks (a logging `povray` ahead of the real one on PATH sees them).
TEST(RenderTest, AStillRendersInBandsOfRowsOnePovrayEach) {
  test::TempDir dir;
  const auto log = dir.path() / "povray.log";
  test::writeText(dir.path() / "povray",
                  "#!/bin/sh\necho \"$*\" >> '" + log.string() + "'\nexec /usr/bin/povray \"$@\"\n");
  std::filesystem::permissions(dir.path() / "povray", std::filesystem::perms::owner_all);
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  setenv("PATH", (dir.path().string() + ":" + saved).c_str(), 1);
  RenderRequest r = request(dir.path() / "asset", "studio", 160, 120);
  r.threads = 2;
  const RenderOutputs out = renderAsset(twoLayerRock(2), r);
  setenv("PATH", saved.c_str(), 1);
  const std::string calls = test::readBytes(log);
  EXPECT_EQ(std::count(calls.begin(), calls.end(), '\n'), 2) << calls;
  EXPECT_NE(calls.find("+WT1 +BS32 +SR1 +ER64"), std::string::npos) << calls;
  EXPECT_NE(calls.find("+WT1 +BS32 +SR65 +ER120"), std::string::npos) << calls;
  // Every row was rendered: the sky's gradient reaches the first and the last row.
  const ExrImage img = readExr(out.render_exr);
  for (const int y : {0, 63, 64, 119})
    EXPECT_GT(img.at("R", 0, y) + img.at("G", 0, y) + img.at("B", 0, y), 0.0f) << "row " << y;
}

TEST(RenderTest, PovrayArgumentsAreExplicit) {
  PovrayJob job;
  job.scene = "scene.pov";
  job.output = "render.exr";
  job.width = 320;
  job.height = 240;
  job.quality = 9;
  job.antialias = 0.3;
  job.threads = 2;
  const auto args = povrayArguments(job);
  const std::vector<std::string> expected = {"povray", "-D",    "-V",  "-P",    "+Iscene.pov", "+Orender.exr", "+FE",
                                             "+W320",  "+H240", "+Q9", "+A0.3", "-J",          "+WT2",         "+BS32"};
  EXPECT_EQ(args, expected);
  // A band: POV-Ray's rows count from 1 and its end row is inclusive.
  job.first_row = 64;
  job.end_row = 128;
  const auto band = povrayArguments(job);
  ASSERT_EQ(band.size(), expected.size() + 2);
  EXPECT_EQ(band[band.size() - 2], "+SR65");
  EXPECT_EQ(band.back(), "+ER128");
}

TEST(RenderTest, WorldToPovSwapsYAndZ) {
  EXPECT_EQ(worldToPov({1, 2, 3}), (Vec3{1, 3, 2}));
}

// One texture per distinct colour; every face corner names the texture of its vertex's colour.
TEST(RenderTest, MeshIncludeSharesTexturesBetweenVerticesOfOneColour) {
  // Two colours by hemisphere, and a third on the equator's vertices that differs from the first
  // only below the rounding step (1/4096): 3 textures would mean no sharing, 2 sharing at that step.
  const auto colour = [](const Pos& p) {
    if (std::abs(p[2] - 1.0f) < 1e-4f) return Color{0.5f, 0.25f, 0.125f + 1e-5f};
    return p[2] > 1.0f ? Color{0.5f, 0.25f, 0.125f} : Color{0.1f, 0.2f, 0.8f};
  };
  const AssetMeshes meshes = asset(icosphere(3, {0, 0, 1}, 1.0f, colour));
  test::TempDir dir;
  const auto file = dir.path() / "rock_mesh.inc";
  writeMeshInclude(meshes, file);
  const std::string text = test::readBytes(file);

  std::smatch m;
  ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(texture_list \{ (\d+),)")));
  ASSERT_EQ(std::stoul(m[1]), 2u);
  std::vector<Color> textures;
  // Each texture names its colour twice (times Rockbake_Dark and Rockbake_Light): read the first.
  const std::regex texture(R"(\[0 rgb <([0-9.e-]+), ([0-9.e-]+), ([0-9.e-]+)> \* Rockbake_Dark\])");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), texture); it != std::sregex_iterator(); ++it)
    textures.push_back({std::stof((*it)[1]), std::stof((*it)[2]), std::stof((*it)[3])});
  ASSERT_EQ(textures.size(), 2u);

  const std::regex face(R"(<(\d+), (\d+), (\d+)>, (\d+), (\d+), (\d+))");
  std::size_t faces = 0;
  const std::size_t faces_at = text.find("face_indices");
  for (auto it = std::sregex_iterator(text.begin() + std::ptrdiff_t(faces_at), text.end(), face);
       it != std::sregex_iterator(); ++it, ++faces)
    for (int k = 0; k < 3; ++k) {
      const std::size_t vertex = std::stoul((*it)[1 + k]), tex = std::stoul((*it)[4 + k]);
      ASSERT_LT(tex, textures.size());
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(textures[tex][c], meshes.rock.colors[vertex][c], 0.5 / 4095) << "vertex " << vertex;
    }
  EXPECT_EQ(faces, meshes.rock.triangles.size());
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

TEST(RenderTest, PovrayTimeoutKillsIt) {
  test::TempDir dir;
  test::writeText(dir.path() / "forever.pov", "#version 3.7;\n#while (1)\n#end\n");
  PovrayJob job;
  job.working_dir = dir.path();
  job.scene = "forever.pov";
  job.output = "out.exr";
  job.width = 16;
  job.height = 16;
  job.timeout = std::chrono::seconds(1);
  const auto start = std::chrono::steady_clock::now();
  try {
    runPovray(job);
    FAIL() << "expected a timeout";
  } catch (const PovrayError& e) {
    EXPECT_NE(std::string(e.what()).find("timed out"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

TEST(RenderTest, RerenderFromAssetFolderNeedsNoMeshes) {
  test::TempDir dir;
  const RenderOutputs first = renderAsset(twoLayerRock(1), request(dir.path(), "debug", 32, 24));
  const ExrImage before = readExr(first.render_exr);
  std::filesystem::remove(first.render_exr);
  RenderRequest again = request(dir.path(), "studio", 32, 24);
  again.template_override = "debug";
  const RenderOutputs second = rerenderAsset(again);
  const ExrImage after = readExr(second.render_exr);
  ASSERT_EQ(before.plane("R").size(), after.plane("R").size());
  for (std::size_t i = 0; i < before.plane("R").size(); ++i) EXPECT_EQ(before.plane("R")[i], after.plane("R")[i]) << i;
  test::TempDir empty;
  EXPECT_THROW(rerenderAsset(request(empty.path(), "debug", 32, 24)), std::runtime_error);
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

// A stand-in POV-Ray that counts its runs in `runs` (in its working folder)
// and fails with `message` on the first `failures` of them, then writes its
// +O output.
std::filesystem::path flakyPovray(const std::filesystem::path& dir, int failures, const std::string& message) {
  const auto script = dir / "flaky-povray";
  test::writeText(script,
                  "#!/bin/sh\n"
                  "n=$(cat runs 2>/dev/null || echo 0); n=$((n + 1)); echo $n > runs\n"
                  "if [ $n -le " +
                      std::to_string(failures) + " ]; then echo '" + message +
                      "' >&2; exit 1; fi\n"
                      "for a in \"$@\"; do case $a in +O*) echo exr > \"${a#+O}\" ;; esac; done\n");
  std::filesystem::permissions(script, std::filesystem::perms::owner_all);
  return script;
}

PovrayJob flakyJob(const std::filesystem::path& dir, const std::filesystem::path& executable) {
  PovrayJob job;
  job.working_dir = dir;
  job.scene = "scene.pov";
  job.output = "out.exr";
  job.executable = executable.string();
  return job;
}

int runs(const std::filesystem::path& dir) {
  return std::stoi(test::readBytes(dir / "runs"));
}

TEST(RenderTest, PovrayWorkerStartupTimeoutIsRetried) {
  test::TempDir dir;
  const auto povray = flakyPovray(dir.path(), 2, kWorkerStartupTimeout);
  EXPECT_NO_THROW(runPovray(flakyJob(dir.path(), povray)));
  EXPECT_EQ(runs(dir.path()), 3);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "out.exr"));
}

TEST(RenderTest, PovrayWorkerStartupTimeoutGivesUpAfterFourRuns) {
  test::TempDir dir;
  const auto povray = flakyPovray(dir.path(), 100, kWorkerStartupTimeout);
  try {
    runPovray(flakyJob(dir.path(), povray));
    FAIL() << "expected a PovrayError";
  } catch (const PovrayError& e) {
    EXPECT_NE(std::string(e.what()).find(kWorkerStartupTimeout), std::string::npos) << e.what();
  }
  EXPECT_EQ(runs(dir.path()), 4);
}

TEST(RenderTest, OtherPovrayFailuresAreNotRetried) {
  test::TempDir dir;
  const auto povray = flakyPovray(dir.path(), 1, "Possible Parse Error: missing brace");
  EXPECT_THROW(runPovray(flakyJob(dir.path(), povray)), PovrayError);
  EXPECT_EQ(runs(dir.path()), 1);
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

// The templates' soft shadows, the antialiasing and the EXR header depend on
// nothing but the asset: one thread or two, the still, every turntable frame
// and their previews are the same bytes (POV-Ray's jitter, which follows the
// thread that renders a block, is off).
TEST(RenderTest, RendersAreTheSameBytesAtAnyThreadCount) {
  test::TempDir dir;
  RenderRequest one = request(dir.path() / "one", "studio", 160, 120, 2);
  one.params.antialias = 0.3;
  one.threads = 1;
  RenderRequest two = one;
  two.asset_dir = dir.path() / "two";
  two.threads = 2;
  const RenderOutputs a = renderAsset(twoLayerRock(3), one);
  const RenderOutputs b = renderAsset(twoLayerRock(3), two);
  EXPECT_EQ(test::readBytes(a.render_exr), test::readBytes(b.render_exr));
  EXPECT_EQ(test::readBytes(a.render_png), test::readBytes(b.render_png));
  // The still in three bands of rows (120 rows: 32, 32 and 56), each its own POV-Ray process,
  // joined: the same bytes as one process, and no band's temporary left behind.
  RenderRequest three = one;
  three.asset_dir = dir.path() / "three";
  three.threads = 3;
  three.params.turntable_frames = 0;
  const RenderOutputs c = renderAsset(twoLayerRock(3), three);
  EXPECT_EQ(test::readBytes(a.render_exr), test::readBytes(c.render_exr));
  for (const auto& entry : std::filesystem::directory_iterator(three.asset_dir))
    EXPECT_EQ(entry.path().filename().string().find(".povray"), std::string::npos) << entry.path();
  ASSERT_EQ(a.turntable_frames.size(), b.turntable_frames.size());
  for (std::size_t i = 0; i < a.turntable_frames.size(); ++i)
    EXPECT_EQ(test::readBytes(a.turntable_frames[i]), test::readBytes(b.turntable_frames[i])) << i;
  EXPECT_EQ(test::readBytes(a.turntable_sheet_png), test::readBytes(b.turntable_sheet_png));
  Imf::InputFile file(a.render_exr.string().c_str());
  EXPECT_EQ(file.header().find("creation"), file.header().end());
}

}  // namespace
}  // namespace rockbake
