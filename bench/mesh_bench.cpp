// The mesh stage on a weathered 128³ asset (figures in bench/README.md).
//
//   BM_MeshExtract:    level sets, smoothing and polygonisation of rock and colluvium
//   BM_MeshAttributes: exposure field and per-vertex sampling (level 0)
//   BM_MeshSubdivide:  Catmull-Clark level 2 of both surfaces, primvars refined
//   BM_MeshExport:     palette + PLY, OBJ + MTL, GLB and two LODs (0.5, 0.25), to a temp folder
//   BM_MeshStage:      all of the above (bakeMeshes); the counter `share` is its
//                      share of the whole bake (simulation, VDB write, mesh stage)
//
// The mesh kernel (docs/mesh-kernel.md) on the refined rock (subdivision 2):
//   BM_EdgeTable:       the edge table of its triangles
//   BM_CheckMesh:       checkMesh (edge table, fold-overs, pieces, volume)
//   BM_RepairFoldOvers: the fold-over repair on a clean surface: the cost of looking
//   BM_MeshLods:        simplifyLods(0.5, 0.25) of both refined surfaces: every
//                       pass, pinch split and repair, no files
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <spdlog/spdlog.h>
#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "export/glb_file.h"
#include "export/obj_file.h"
#include "export/ply_file.h"
#include "export/vdb_file.h"
#include "geometry/edge_table.h"
#include "geometry/mesh_checks.h"
#include "mesh/bake_attributes.h"
#include "mesh/extract_surfaces.h"
#include "mesh/fold_over_repair.h"
#include "mesh/mesh_defects.h"
#include "mesh/simplify_lods.h"
#include "mesh/subdivide.h"
#include "pipeline/bake_meshes.h"
#include "pipeline/export_meshes.h"
#include "platform/colour.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

namespace rockbake {
namespace {

// A 2.4 × 2.4 × 3.6 box on the ground in a 128-voxel domain, two durability
// layers, rockfall and colluvium on, 16 cycles: a weathered asset with both surfaces.
Preset assetPreset() {
  Preset p;
  p.name = "mesh-bench";
  p.seed = 3;
  p.grid.size = {4.0, 4.0, 4.0};
  p.grid.resolution = 128;
  p.grid.ground = true;
  p.shape.kind = BoxShape{{2.4, 2.4, 3.6}};
  p.durability.graph.points = {{0.0, 1.0}, {0.4, 0.5}, {0.6, 2.0}, {1.0, 1.0}};
  BubbleBand band;
  band.up_to = 1.0;
  band.bubble.kind = BubbleSpec::Kind::Sphere;
  band.bubble.extents = {0.2, 0, 0};
  band.spheroidal = 0.8;
  band.cavernous = 0.2;
  p.bubbles = {band};
  p.response = {ResponseParams::Kind::Power, 1.0, {}};
  p.rockfall.mode = RockfallMode::Drop;
  p.colluvium.yield = 0.5;
  p.stop.cycles = 16;
  p.mesh.subdivision = 2;
  p.mesh.lods = {0.5, 0.25};
  return p;
}

struct Asset {
  Preset preset = assetPreset();
  VoxelRock rock;
  double simulate_seconds = 0;  // initial rock, cycles and VDB write
  std::filesystem::path dir;
};

const Asset& asset() {
  static const Asset a = [] {
    Asset a;
    a.dir = std::filesystem::temp_directory_path() / ("rockbake-mesh-bench-" + std::to_string(::getpid()));
    const auto start = std::chrono::steady_clock::now();
    a.rock = weatherRock(buildInitialRock(resolveShape(a.preset), a.preset), a.preset).rock;
    writeRockVdb(a.rock, a.dir / "rock.vdb");
    a.simulate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return a;
  }();
  return a;
}

AssetMeshes sampled() {
  const Asset& a = asset();
  const std::vector<float> exposure = exposureField(a.rock, a.preset.bubbles);
  return sampleAttributes(extractSurfaces(a.rock, {a.preset.mesh.smoothing}), {&a.rock, &exposure});
}

// Both surfaces after attributes and Catmull-Clark level 2, as the LODs start from.
const AssetMeshes& refined() {
  static const AssetMeshes m = [] {
    AssetMeshes r = sampled();
    r.rock = subdivideSurface(r.rock, {2});
    r.colluvium = subdivideSurface(r.colluvium, {2});
    return applyPalette(std::move(r), paletteParams(asset().rock, asset().preset.bake));
  }();
  return m;
}

void counters(benchmark::State& state, const AssetMeshes& m) {
  state.counters["rock_triangles"] = double(m.rock.triangles.size() + 2 * m.rock.quads.size());
  state.counters["colluvium_triangles"] = double(m.colluvium.triangles.size() + 2 * m.colluvium.quads.size());
}

void BM_MeshExtract(benchmark::State& state) {
  const Asset& a = asset();
  AssetMeshes m;
  for (auto _ : state) m = extractSurfaces(a.rock, {a.preset.mesh.smoothing});
  counters(state, m);
}

void BM_MeshAttributes(benchmark::State& state) {
  const Asset& a = asset();
  const AssetMeshes base = extractSurfaces(a.rock, {a.preset.mesh.smoothing});
  for (auto _ : state) {
    const std::vector<float> exposure = exposureField(a.rock, a.preset.bubbles);
    benchmark::DoNotOptimize(sampleAttributes(base, {&a.rock, &exposure}));
  }
}

void BM_MeshSubdivide(benchmark::State& state) {
  const AssetMeshes base = sampled();
  AssetMeshes m;
  for (auto _ : state) {
    m.rock = subdivideSurface(base.rock, {int(state.range(0))});
    m.colluvium = subdivideSurface(base.colluvium, {int(state.range(0))});
  }
  counters(state, m);
}

void BM_MeshExport(benchmark::State& state) {
  const Asset& a = asset();
  AssetMeshes m = sampled();
  m.rock = subdivideSurface(m.rock, {2});
  m.colluvium = subdivideSurface(m.colluvium, {2});
  for (auto _ : state) {
    m = applyPalette(std::move(m), paletteParams(a.rock, a.preset.bake));
    writePly(m.rock, a.dir / "rock.ply");
    writePly(m.colluvium, a.dir / "colluvium.ply");
    writeObj(m, a.dir / "rock.obj");
    writeGlb(m, a.dir / "rock.glb");
    const std::vector<AssetMeshes> lods = simplifyLods(m, {a.preset.mesh.lods});
    for (std::size_t i = 0; i < lods.size(); ++i)
      writeGlb(lods[i], a.dir / ("rock_lod" + std::to_string(i + 1) + ".glb"));
  }
  counters(state, m);
  state.counters["obj_MB"] = double(std::filesystem::file_size(a.dir / "rock.obj")) / 1e6;
  state.counters["glb_MB"] = double(std::filesystem::file_size(a.dir / "rock.glb")) / 1e6;
}

void BM_MeshStage(benchmark::State& state) {
  const Asset& a = asset();
  double seconds = 0;
  int runs = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(exportMeshes(bakeMeshes(a.rock, a.preset), nullptr, a.preset, a.dir));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++runs;
  }
  const double mesh = seconds / runs;
  state.counters["simulate_s"] = a.simulate_seconds;
  state.counters["share"] = mesh / (mesh + a.simulate_seconds);
}

void BM_EdgeTable(benchmark::State& state) {
  const SurfaceMesh& rock = refined().rock;
  for (auto _ : state) benchmark::DoNotOptimize(EdgeTable(rock.triangles).openEdgeCount());
  state.counters["triangles"] = double(rock.triangles.size());
}

void BM_CheckMesh(benchmark::State& state) {
  const SurfaceMesh& rock = refined().rock;
  for (auto _ : state) benchmark::DoNotOptimize(checkMesh(rock));
  state.counters["triangles"] = double(rock.triangles.size());
}

void BM_RepairFoldOvers(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    SurfaceMesh rock = refined().rock;
    state.ResumeTiming();
    benchmark::DoNotOptimize(repairFoldOvers(rock));
  }
}

void BM_MeshLods(benchmark::State& state) {
  const AssetMeshes& m = refined();
  std::vector<AssetMeshes> lods;
  for (auto _ : state) lods = simplifyLods(m, {asset().preset.mesh.lods});
  state.counters["lod1_triangles"] = double(lods[0].rock.triangles.size() + lods[0].colluvium.triangles.size());
}

BENCHMARK(BM_MeshExtract)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_MeshAttributes)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_MeshSubdivide)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_MeshExport)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_MeshStage)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_EdgeTable)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_CheckMesh)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_RepairFoldOvers)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_MeshLods)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace rockbake

int main(int argc, char** argv) {
  if (std::getenv("ROCKBAKE_BENCH_DEBUG")) spdlog::set_level(spdlog::level::debug);  // per-file and per-LOD log
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::error_code ignored;
  std::filesystem::remove_all(
      std::filesystem::temp_directory_path() / ("rockbake-mesh-bench-" + std::to_string(::getpid())), ignored);
  return 0;
}
