// Small helpers shared by the tests: in-memory presets, temporary folders,
// running the real rockbake executable, shape measurements.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"
#include "platform/child_process.h"
#include "preset/preset.h"

namespace rockbake::test {

// A 24-voxel box preset, 6 cycles (time 0.5 at h = 2 / 24): a whole bake in a
// few tens of milliseconds. Twelve lines, so a key appended to it is on line 13.
// It is tests/data/small.yaml, embedded at build time; the shell and JavaScript
// tests (tests/review/library.mjs, tests/install/common.sh,
// tests/render/helper_programs_test.sh) read that file too.
extern const char* const kSmallPreset;

// A free-floating (ground off) cube of `cube` world units in a domain of the
// same size, resolution `resolution`, one sphere bubble of `bubble_radius`
// world units, spheroidal only, linear response, uniform durability 1,
// no rockfall and no colluvium: weathering alone.
Preset cubePreset(double cube, int resolution, double bubble_radius);

// A fresh, empty folder under the system temp folder, removed on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exit_status = -1;
  std::string output;  // stdout and stderr together
};
// Runs the built rockbake executable with `args` (shell-quoted here).
CommandResult runRockbake(const std::vector<std::string>& args);
// The same, after `shell_prefix` in the same shell command line: "ulimit -v 600000; ", "ENV=value ".
// A rockbake ended by a signal gives 128 + the signal's number, as shells report it.
CommandResult runRockbakeUnder(const std::string& shell_prefix, const std::vector<std::string>& args);
// Starts the built rockbake executable with `args`, its output and errors to `log` (created or
// truncated), its input /dev/null, and returns once it runs (ChildStartError if it cannot start),
// not waiting for it. It stays in this process's group, so a signal a test sends to its pid
// (SIGINT, SIGKILL) reaches rockbake alone. It is killed if the calling thread ends first (the
// test binary killed at its timeout), and when the returned object goes while it still runs.
std::unique_ptr<ChildProcess> startRockbake(const std::vector<std::string>& args, const std::filesystem::path& log);

std::filesystem::path sourceDir();
void writeText(const std::filesystem::path& file, const std::string& text);
std::string readBytes(const std::filesystem::path& file);

// Rock voxels with at least one face neighbour that is not rock.
std::vector<Vec3d> surfaceVoxelCentres(const VoxelRock& rock);
Vec3d rockCentroid(const VoxelRock& rock);
// Coefficient of variation of the surface voxels' distances from the centroid.
double surfaceDistanceSpread(const VoxelRock& rock);
// Per layer z, the radius of a disc of the layer's rock area (world units): a column's profile.
std::vector<double> layerRadii(const VoxelRock& rock);
// Pearson's correlation of two equally long series.
double pearson(const std::vector<double>& a, const std::vector<double>& b);
// The 6-connected components of one material's voxels (a plain flood fill, not rockbake's code).
std::size_t voxelComponents(const VoxelRock& rock, Material material = Material::Rock);

// A random grid for exact-count and round-trip checks: each cell is rock with
// probability 0.8 × fill, colluvium with 0.2 × fill, else air (counter-hashed
// from `seed`); rock gets a durability in [0.1, 3), integrity 1. Layout: h =
// 0.125, margin 2, origin (-1.25, -0.75, 0), ground as given.
VoxelRock randomRock(int nx, int ny, int nz, std::uint64_t seed, double fill = 0.6, bool ground = true);

// Reproducible values spread over many magnitudes (a pure function of i), so a changed order of
// operations shows up as a changed last bit; and the bitwise comparison that sees it.
double spreadValue(std::uint64_t i);
Vec3d randomVec3d(std::uint64_t i);
Vec3f randomVec3f(std::uint64_t i);
bool sameBits(double a, double b);

// A unit-radius icosphere about the origin, `levels` times subdivided,
// outward-facing (20 · 4^levels triangles).
TriangleMesh icosphere(int levels);

}  // namespace rockbake::test
