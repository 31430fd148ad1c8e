// The turntable movie (docs/rendering.md, "Turntable movie"): read back by
// ffprobe, the same bytes from the same frames, FFmpeg's absence and failure
// reported, and a library whose every asset has one.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "render/preview.h"
#include "render/render_asset.h"
#include "render/turntable_movie.h"
#include "test_support.h"

namespace rockbake {
namespace {

std::string shellOutput(const std::string& command) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  return out;
}

// The movie's one video stream as ffprobe reads it, frames counted by decoding.
nlohmann::json probe(const std::filesystem::path& movie) {
  const std::string out = shellOutput(
      "ffprobe -v error -count_frames -select_streams v -show_entries "
      "stream=codec_name,profile,pix_fmt,width,height,r_frame_rate,nb_read_frames,color_space -of json '" +
      movie.string() + "'");
  const nlohmann::json j = nlohmann::json::parse(out, nullptr, false);
  if (j.is_discarded() || !j.contains("streams") || j["streams"].size() != 1) return nullptr;
  return j["streams"][0];
}

// A sphere, coloured by side so the views differ.
AssetMeshes ball() {
  const TriangleMesh sphere = test::icosphere(2);
  AssetMeshes a;
  a.rock.name = "rock";
  for (const auto& d : sphere.positions) {
    a.rock.positions.push_back({float(d[0]), float(d[1]), float(d[2]) + 1.0f});
    a.rock.normals.push_back({float(d[0]), float(d[1]), float(d[2])});
    a.rock.colors.push_back({d[0] > 0 ? 0.8f : 0.1f, d[1] > 0 ? 0.6f : 0.1f, 0.2f});
  }
  a.rock.triangles = sphere.triangles;
  a.bounds_min = {-1, -1, 0};
  a.bounds_max = {1, 1, 2};
  return a;
}

RenderRequest turntable(const std::filesystem::path& dir, int frames, int fps) {
  RenderRequest r;
  r.asset_dir = dir;
  r.params.width = 41;  // odd: the movie rounds it up to 42 × 32
  r.params.height = 31;
  r.params.antialias = 0;
  r.params.turntable_frames = frames;
  r.params.turntable_fps = fps;
  r.params.turntable_lookdev = true;
  r.preset_name = "ball";
  r.threads = 2;
  r.timeout = std::chrono::seconds(60);
  return r;
}

TEST(TurntableMovie, IsH264HighYuv420pOneFramePerViewAtItsRate) {
  test::TempDir dir;
  const RenderOutputs out = renderAsset(ball(), turntable(dir.path(), 5, 12));
  ASSERT_EQ(out.turntable_movie, dir.path() / "turntable.mp4");
  const nlohmann::json s = probe(out.turntable_movie);
  ASSERT_TRUE(s.is_object()) << "ffprobe could not read " << out.turntable_movie;
  EXPECT_EQ(s.value("codec_name", ""), "h264");
  EXPECT_EQ(s.value("profile", ""), "High");
  EXPECT_EQ(s.value("pix_fmt", ""), "yuv420p");
  EXPECT_EQ(s.value("color_space", ""), "bt709");
  EXPECT_EQ(s.value("width", 0), 42);
  EXPECT_EQ(s.value("height", 0), 32);
  EXPECT_EQ(s.value("r_frame_rate", ""), "12/1");
  EXPECT_EQ(s.value("nb_read_frames", ""), "5");
  // Nothing but the movie is left beside it.
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_NE(e.path().filename().string().front(), '.') << e.path();
}

// The movie has render.png's look: its first frame, decoded by FFmpeg back to
// RGB, averages what the OCIO display transform gives for the EXR to within
// three levels in each channel, with the same contrast within 5 % (a range
// read as full or limited the wrong way scales it by 219/255, 14 %).
TEST(TurntableMovie, LooksLikeTheDisplayTransform) {
  test::TempDir dir;
  RenderRequest request = turntable(dir.path(), 2, 24);
  request.params.width = 160;
  request.params.height = 120;
  const RenderOutputs out = renderAsset(ball(), request);
  const std::string rgb =
      shellOutput("ffmpeg -v error -i '" + out.turntable_movie.string() + "' -frames:v 1 -f rawvideo -pix_fmt rgb24 -");
  const RgbImage display = exrToDisplay(out.turntable_frames[0]);
  ASSERT_EQ(rgb.size(), std::size_t(160 * 120 * 3));
  ASSERT_EQ(display.pixels.size(), rgb.size());
  for (int c = 0; c < 3; ++c) {
    double movie = 0, expected = 0, movie2 = 0, expected2 = 0;
    for (std::size_t i = std::size_t(c); i < rgb.size(); i += 3) {
      const double m = double(static_cast<unsigned char>(rgb[i])), e = double(display.pixels[i]);
      movie += m, expected += e, movie2 += m * m, expected2 += e * e;
    }
    const double n = double(rgb.size() / 3);
    EXPECT_NEAR(movie / n, expected / n, 3.0) << "channel " << c;
    const double movie_sd = std::sqrt(movie2 / n - (movie / n) * (movie / n));
    const double expected_sd = std::sqrt(expected2 / n - (expected / n) * (expected / n));
    EXPECT_NEAR(movie_sd / expected_sd, 1.0, 0.05) << "channel " << c;
  }
}

TEST(TurntableMovie, SameFramesGiveTheSameBytes) {
  test::TempDir dir;
  const RenderOutputs out = renderAsset(ball(), turntable(dir.path(), 3, 24));
  TurntableMovieJob job;
  job.frames = out.turntable_frames;
  job.target = dir.path() / "again.mp4";
  writeTurntableMovie(job);
  EXPECT_EQ(test::readBytes(job.target), test::readBytes(out.turntable_movie));
  EXPECT_EQ(movieFrameSize(41, 31), (std::array<int, 2>{42, 32}));
  EXPECT_EQ(movieFrameSize(40, 30), (std::array<int, 2>{40, 30}));
}

TEST(TurntableMovie, MissingOrFailingFfmpegIsAClearErrorAndLeavesNothing) {
  test::TempDir dir;
  const RenderOutputs out = renderAsset(ball(), turntable(dir.path(), 2, 24));
  TurntableMovieJob job;
  job.frames = out.turntable_frames;
  job.target = dir.path() / "movie.mp4";
  job.executable = "rockbake-no-such-ffmpeg";
  try {
    writeTurntableMovie(job);
    FAIL() << "no error";
  } catch (const MovieError& e) {
    EXPECT_NE(std::string(e.what()).find("apt-get install ffmpeg"), std::string::npos) << e.what();
  }
  // An FFmpeg that refuses: its own message reaches the user.
  const auto fake = dir.path() / "fake-ffmpeg";
  test::writeText(fake, "#!/bin/sh\necho 'Unknown encoder libx264' >&2\nexit 1\n");
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  job.executable = fake.string();
  try {
    writeTurntableMovie(job);
    FAIL() << "no error";
  } catch (const MovieError& e) {
    EXPECT_NE(std::string(e.what()).find("Unknown encoder libx264"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(job.target));
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_NE(e.path().filename().string().front(), '.') << e.path();
}

// Two presets × two seeds through `rockbake library`: every asset's movie is
// H.264 yuv420p with one frame per view, and asset.json and index.json link it.
TEST(TurntableMovie, EveryAssetOfALibraryHasOne) {
  test::TempDir dir;
  const std::string tail = "render: {width: 64, height: 48, antialias: 0, turntable: {frames: 3}}\n";
  test::writeText(dir.path() / "small.yaml", std::string(test::kSmallPreset) + tail);
  std::string other = test::kSmallPreset;
  other.replace(other.find("name: small"), 11, "name: other");
  const std::string cube = "box: {size: [1.5, 1.5, 1.5]}";
  other.replace(other.find(cube), cube.size(), "box: {size: [1.2, 1.6, 1.0]}");
  test::writeText(dir.path() / "other.yaml", other + tail);
  test::writeText(dir.path() / "lib.yaml",
                  "- {preset: small.yaml, seeds: [1, 2]}\n- {preset: other.yaml, seeds: [1, 2]}\n");
  const auto out = dir.path() / "out";
  const test::CommandResult r =
      test::runRockbake({"library", (dir.path() / "lib.yaml").string(), "-o", out.string(), "--jobs", "2"});
  ASSERT_EQ(r.exit_status, 0) << r.output;
  const nlohmann::json index = nlohmann::json::parse(test::readBytes(out / "index.json"));
  ASSERT_EQ(index["assets"].size(), 4u);
  for (const auto& a : index["assets"]) {
    const std::string name = a["name"];
    ASSERT_EQ(a["movie"], name + "/turntable.mp4") << name;
    const nlohmann::json asset = nlohmann::json::parse(test::readBytes(out / name / "asset.json"));
    EXPECT_EQ(asset["movie"], "turntable.mp4") << name;
    const nlohmann::json s = probe(out / name / "turntable.mp4");
    ASSERT_TRUE(s.is_object()) << name;
    EXPECT_EQ(s.value("codec_name", ""), "h264") << name;
    EXPECT_EQ(s.value("pix_fmt", ""), "yuv420p") << name;
    EXPECT_EQ(s.value("nb_read_frames", ""), "3") << name;
    EXPECT_EQ(s.value("r_frame_rate", ""), "24/1") << name;
  }
}

}  // namespace
}  // namespace rockbake
