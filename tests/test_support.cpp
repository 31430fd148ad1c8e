#include "test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/hash.h"

namespace rockbake::test {

// tests/data/small.yaml, a C++ raw string written by tests/CMakeLists.txt into the build folder.
const char* const kSmallPreset =
#include "small_preset.inc"
    ;

Preset cubePreset(double cube, int resolution, double bubble_radius) {
  Preset p;
  p.name = "cube";
  p.seed = 1;
  p.grid.size = {cube, cube, cube};
  p.grid.resolution = resolution;
  p.grid.ground = false;
  p.shape.kind = BoxShape{{cube, cube, cube}};
  BubbleBand band;
  band.up_to = 1.0;
  band.bubble.kind = BubbleSpec::Kind::Sphere;
  band.bubble.extents = {bubble_radius, 0, 0};
  band.spheroidal = 1.0;
  band.cavernous = 0.0;
  p.bubbles = {band};
  p.rockfall.mode = RockfallMode::Off;
  p.colluvium.yield = 0.0;
  p.stop.cycles = 1;
  return p;
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("rockbake-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

namespace {
std::string shellQuote(const std::string& s) {
  std::string quoted = "'";
  for (char c : s) quoted += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}
}  // namespace

CommandResult runRockbake(const std::vector<std::string>& args) {
  return runRockbakeUnder("", args);
}

CommandResult runRockbakeUnder(const std::string& shell_prefix, const std::vector<std::string>& args) {
  std::string command = shell_prefix + shellQuote(ROCKBAKE_EXECUTABLE);
  for (const auto& a : args) {
    command += ' ';
    command += shellQuote(a);
  }
  command += " 2>&1";
  CommandResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
  return result;
}

std::unique_ptr<ChildProcess> startRockbake(const std::vector<std::string>& args, const std::filesystem::path& log) {
  ChildOptions options;
  options.argv = {ROCKBAKE_EXECUTABLE};
  options.argv.insert(options.argv.end(), args.begin(), args.end());
  options.output_file = log;
  options.own_group = false;
  options.end_with_parent = true;
  return std::make_unique<ChildProcess>(options);
}

std::filesystem::path sourceDir() {
  return ROCKBAKE_SOURCE_DIR;
}

void writeText(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
}

std::string readBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::vector<Vec3d> surfaceVoxelCentres(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  const auto isRock = [&](int x, int y, int z) {
    return g.contains(x, y, z) && rock.material[g.index(x, y, z)] == Material::Rock;
  };
  std::vector<Vec3d> centres;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (isRock(x, y, z) && !(isRock(x - 1, y, z) && isRock(x + 1, y, z) && isRock(x, y - 1, z) &&
                                 isRock(x, y + 1, z) && isRock(x, y, z - 1) && isRock(x, y, z + 1)))
          centres.push_back(g.center(x, y, z));
  return centres;
}

Vec3d rockCentroid(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  Vec3d sum{0, 0, 0};
  double n = 0;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] == Material::Rock) {
          const Vec3d c = g.center(x, y, z);
          for (int a = 0; a < 3; ++a) sum[a] += c[a];
          n += 1;
        }
  return {sum[0] / n, sum[1] / n, sum[2] / n};
}

double surfaceDistanceSpread(const VoxelRock& rock) {
  const Vec3d c = rockCentroid(rock);
  std::vector<double> d;
  for (const auto& p : surfaceVoxelCentres(rock)) d.push_back(std::hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]));
  double mean = 0;
  for (double v : d) mean += v;
  mean /= double(d.size());
  double var = 0;
  for (double v : d) var += (v - mean) * (v - mean);
  return std::sqrt(var / double(d.size())) / mean;
}

VoxelRock randomRock(int nx, int ny, int nz, std::uint64_t seed, double fill, bool ground) {
  VoxelRock rock;
  GridLayout& g = rock.layout;
  g.nx = nx, g.ny = ny, g.nz = nz;
  g.margin = 2;
  g.h = 0.125;
  g.origin = {-1.25, -0.75, 0.0};
  g.ground = ground;
  rock.material.assign(g.cellCount(), Material::Air);
  for (std::size_t i = 0; i < rock.material.size(); ++i) {
    const double u = unitInterval(counterHash(seed, purposeId("test-fill"), 0, i));
    if (u < fill * 0.8)
      rock.material[i] = Material::Rock;
    else if (u < fill)
      rock.material[i] = Material::Colluvium;
  }
  resetRockValues(rock);
  for (std::size_t i = 0; i < rock.material.size(); ++i)
    if (rock.material[i] == Material::Rock)
      rock.durability.set(i, float(0.1 + 2.9 * unitInterval(counterHash(seed, purposeId("test-durability"), 0, i))));
  return rock;
}

TriangleMesh icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriangleMesh m;
  m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  const auto normalise = [](std::array<double, 3> p) {
    const double l = std::hypot(p[0], p[1], p[2]);
    return std::array<double, 3>{p[0] / l, p[1] / l, p[2] / l};
  };
  for (auto& p : m.positions) p = normalise(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    const auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      if (const auto it = middle.find(key); it != middle.end()) return it->second;
      const auto& pa = m.positions[a];
      const auto& pb = m.positions[b];
      m.positions.push_back(normalise({pa[0] + pb[0], pa[1] + pb[1], pa[2] + pb[2]}));
      return middle[key] = std::uint32_t(m.positions.size() - 1);
    };
    std::vector<std::array<std::uint32_t, 3>> finer;
    for (const auto& [a, b, c] : m.triangles) {
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    m.triangles = finer;
  }
  return m;
}

std::vector<double> layerRadii(const VoxelRock& rock) {
  const GridLayout& g = rock.layout;
  std::vector<double> radii(std::size_t(g.nz), 0.0);
  for (int z = 0; z < g.nz; ++z) {
    std::size_t n = 0;
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) n += rock.material[g.index(x, y, z)] == Material::Rock;
    radii[std::size_t(z)] = std::sqrt(double(n) * g.h * g.h / M_PI);
  }
  return radii;
}

std::size_t voxelComponents(const VoxelRock& rock, Material material) {
  const GridLayout& g = rock.layout;
  std::vector<char> seen(rock.material.size(), 0);
  std::size_t components = 0;
  std::vector<std::array<int, 3>> stack;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const std::size_t i = g.index(x, y, z);
        if (seen[i] || rock.material[i] != material) continue;
        ++components;
        seen[i] = 1;
        stack.push_back({x, y, z});
        while (!stack.empty()) {
          const auto c = stack.back();
          stack.pop_back();
          for (int a = 0; a < 3; ++a)
            for (int s : {-1, 1}) {
              auto n = c;
              n[a] += s;
              if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= g.nx || n[1] >= g.ny || n[2] >= g.nz) continue;
              const std::size_t j = g.index(n[0], n[1], n[2]);
              if (!seen[j] && rock.material[j] == material) seen[j] = 1, stack.push_back(n);
            }
        }
      }
  return components;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= double(a.size()), mb /= double(b.size());
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

double spreadValue(std::uint64_t i) {
  const std::uint64_t h = mix64(i);
  return (double(h >> 11) / double(1ull << 53) - 0.5) * std::ldexp(1.0, int(h % 40) - 20);
}
Vec3d randomVec3d(std::uint64_t i) {
  return {spreadValue(3 * i), spreadValue(3 * i + 1), spreadValue(3 * i + 2)};
}
Vec3f randomVec3f(std::uint64_t i) {
  return toVec3f(randomVec3d(i));
}
bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace rockbake::test
