#include "pipeline/bake_asset.h"

#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "compress/compressed_set.h"
#include "core/error.h"
#include "export/vdb_file.h"
#include "mesh/extract_surfaces.h"
#include "pipeline/asset_folder.h"
#include "pipeline/asset_json.h"
#include "pipeline/bake_clasts.h"
#include "pipeline/bake_collision.h"
#include "pipeline/bake_meshes.h"
#include "pipeline/checkpoint.h"
#include "pipeline/delivery_profile.h"
#include "pipeline/export_meshes.h"
#include "pipeline/individual_json.h"
#include "pipeline/manifest.h"
#include "pipeline/read_inputs.h"
#include "platform/atomic_file.h"
#include "platform/side_by_side.h"
#include "platform/stopwatch.h"
#include "preset/preset_json.h"
#include "preset/schema.h"
#include "render/render_asset.h"
#include "sim/grid_layout.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// What every phase of one bake shares: what it bakes, the staging folder it writes into (taken, with the
// asset's lock and the check that OUT/<name> may be replaced, before any work), the clock and the timings.
struct Bake {
  Bake(const Preset& given, const BakeOptions& options)
      : given(given),
        preset(presetAsBaked(given, options)),
        options(options),
        stages(options.stages.applied()),
        asset_dir(options.out_dir / preset.name),
        staging(asset_dir, outOfMemoryMessage(preset), options.lock),
        before(beginAssetFolder(staging.path())),
        delivery(deliveryConventions(preset, staging.path())) {
    timings.add("load", options.load_seconds);
  }

  const fs::path& dir() const { return staging.path(); }
  // At every cycle and phase boundary (pipeline/bake_phases.h): the studio's progress bar, and a line in
  // the log when a phase after the simulation starts (each can take seconds: the log says what the bake
  // is doing).
  void progress(std::string_view phase, double done = 0.0, double of = 1.0) const {
    if (options.progress) options.progress(bakeProgress(phase, done, of), std::string(phase));
  }
  void startPhase(std::string_view phase) const {
    progress(phase);
    if (const std::string_view doing = bakePhase(phase).doing; !doing.empty())
      spdlog::info("{}: {} ({:.1f} s in)", preset.name, doing, since_start.elapsed() + options.load_seconds);
  }
  void checkCancel() const {
    if (options.cancel && options.cancel->load()) throw BakeCancelled();
  }

  const Preset& given;  // as the caller gave it: what checkpoints record
  const Preset preset;  // presetAsBaked: what every phase bakes
  const BakeOptions& options;
  const BakeStages stages;  // what runs, applied
  const fs::path asset_dir;
  Stopwatch clock;        // lapped phase by phase
  Stopwatch since_start;  // never lapped: the log's "s in"
  StagingFolder staging;
  const AssetFolderSnapshot before;
  const DeliveryConventions delivery;  // the profile's names, unit and maps (pipeline/delivery_profile.h)
  PhaseTimes timings;                  // stats.json's "stages" (pipeline/bake_phases.h)
};

// A simulation ready to run: from the initial rock, or from a checkpoint's state (`rockbake resume`).
struct SimulationStart {
  std::unique_ptr<WeatheringSimulation> simulation;
  std::size_t initial_rock = 0;
  json cycles_before = json::array();  // a resumed bake's cycles up to its checkpoint
};

// The simulation's result, all the later phases need of it.
struct Weathered {
  VoxelRock rock;                   // without integrity, which no later phase reads
  std::vector<BubbleBand> bubbles;  // the bubble graph in effect at the end (the curvature attribute's)
  json cycles;                      // every cycle's statistics, a checkpoint's first
  std::size_t initial_rock = 0, final_rock = 0, colluvium = 0;
};

json cyclesToJson(const std::vector<CycleStats>& cycles) {
  json list = json::array();
  for (const auto& c : cycles)
    list.push_back({{"cycle", c.cycle},
                    {"time", c.time},
                    {"rock", c.rock},
                    {"exposed", c.exposed},
                    {"decimated", c.decimated},
                    {"colluvium", c.colluvium},
                    {"fallen", c.fallen},
                    {"removed", c.removed},
                    {"deposited", c.deposited},
                    {"crumbled", c.crumbled}});
  return list;
}

json concatenated(json first, const json& then) {
  for (const auto& entry : then) first.push_back(entry);
  return first;
}

std::string readTextFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string() + " for its checkpoints");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void checkSameGrid(const Preset& preset, const GridLayout& was) {
  const GridLayout now = computeGridLayout(preset);
  if (was.nx != now.nx || was.ny != now.ny || was.nz != now.nz || was.margin != now.margin || was.h != now.h)
    throw InputError(preset.locate("grid"), "grid",
                     fmt::format("the checkpoint's grid is {}×{}×{} voxels of {:.4g} and this preset's {}×{}×{} of "
                                 "{:.4g}",
                                 was.nx, was.ny, was.nz, was.h, now.nx, now.ny, now.nz, now.h),
                     "grid, shape, resolution and bubbles larger than the checkpoint's margin cannot change on "
                     "resume; bake from the start instead");
}

SimulationStart startSimulation(Bake& bake, const ResolvedShape& shape) {
  const Preset& preset = bake.preset;
  SimulationStart start;
  if (const Checkpoint* resume = bake.options.resume) {
    checkSameGrid(preset, resume->snapshot.rock.layout);
    start.simulation = std::make_unique<WeatheringSimulation>(resume->snapshot, preset);
    start.initial_rock = resume->snapshot.initial_rock;
    start.cycles_before = resume->cycles;
  } else {
    std::string clipped;
    VoxelRock initial = buildInitialRock(shape, preset, &clipped);
    if (!clipped.empty()) spdlog::warn("{}: {}", preset.name, clipped);  // in a library, the job's name
    start.initial_rock = initial.count(Material::Rock);
    if (start.initial_rock == 0)
      throw InputError(preset.locate("shape"), "shape", "the shape covers no voxel of the grid",
                       "check its size and center against grid.size, or raise grid.resolution");
    start.simulation = std::make_unique<WeatheringSimulation>(std::move(initial), preset);
  }
  bake.timings.add("shape", bake.clock.lap());
  const GridLayout& g = start.simulation->rock().layout;
  spdlog::info("{}: {}×{}×{} voxels of {:.4g} units, {} rock voxels, {} cycles{}", preset.name, g.nx, g.ny, g.nz, g.h,
               start.initial_rock, plannedCycles(preset, g.h),
               bake.options.resume ? fmt::format(" (resumed at cycle {})", start.simulation->cycle()) : "");
  return start;
}

// Writes OUT/<name>/checkpoints/<time>.rbk each time the simulation passes a multiple of
// options.checkpoint_every, with the text and overrides that give the preset, so that resume can read it
// again and tell whether it changed.
class CheckpointWriter {
 public:
  CheckpointWriter(const Bake& bake, const SimulationStart& start)
      : bake_(bake), every_(bake.options.checkpoint_every) {
    if (every_ <= 0.0) return;
    const Preset& preset = bake.given;
    const Checkpoint* resume = bake.options.resume;
    checkpoint_.preset_file = fs::absolute(preset.file);
    checkpoint_.preset_text = resume ? resume->preset_text : readTextFile(preset.file);
    checkpoint_.overrides = bake.options.manifest.overrides;
    checkpoint_.preset = presetToJson(preset);
    checkpoint_.preset_hash = presetFingerprint(preset, {});
    cycles_before_ = start.cycles_before;
    h_ = start.simulation->rock().layout.h;
    next_ = every_ * (std::floor(start.simulation->cycle() * h_ / every_ + 1e-9) + 1.0);
  }

  void afterCycle(const WeatheringSimulation& simulation, const std::vector<CycleStats>& cycles) {
    const double time = cycles.back().time;
    if (every_ <= 0.0 || time < next_ - 1e-9 * h_ || simulation.finished()) return;
    checkpoint_.snapshot = simulation.snapshot();
    checkpoint_.cycles = concatenated(cycles_before_, cyclesToJson(cycles));
    const fs::path file = bake_.dir() / "checkpoints" / checkpointFileName(time);
    writeCheckpoint(file, checkpoint_);
    spdlog::info("{}: checkpoint {}", bake_.preset.name, file.string());
    while (next_ <= time + 1e-9 * h_) next_ += every_;
  }

 private:
  const Bake& bake_;
  const double every_;
  double h_ = 1.0, next_ = 0.0;
  json cycles_before_;
  Checkpoint checkpoint_;
};

Weathered simulate(Bake& bake, SimulationStart start) {
  WeatheringSimulation& simulation = *start.simulation;
  const int planned = plannedCycles(bake.preset, simulation.rock().layout.h);
  CheckpointWriter checkpoints(bake, start);
  std::vector<CycleStats> cycles;
  for (int last_percent = -1; !simulation.finished();) {
    const CycleStats& c = cycles.emplace_back(simulation.step());
    bake.checkCancel();
    bake.progress("simulate", c.cycle, planned);
    if (const int percent = 100 * c.cycle / planned; percent / 10 != last_percent / 10) {
      spdlog::info("{}: cycle {}/{} ({}%), {} rock, {} exposed, {} decimated", bake.preset.name, c.cycle, planned,
                   percent, c.rock, c.exposed, c.decimated);
      last_percent = percent;
    }
    checkpoints.afterCycle(simulation, cycles);
  }
  Weathered weathered;
  weathered.bubbles = simulation.activeParams().bubbles;
  weathered.rock = simulation.release();
  start.simulation.reset();  // its working state (air field, bit planes, work lists) is not needed past here
  bake.timings.add("simulate", bake.clock.lap());
  PhaseTimes parts;  // listed even when no cycle ran (a resume at the end)
  for (const char* part : {"curvature", "colluvium", "rockfall", "history"}) parts.add(part, 0.0);
  for (const auto& c : cycles) parts.add(c.times);
  bake.timings.add(parts, "simulate_");
  weathered.cycles = concatenated(std::move(start.cycles_before), cyclesToJson(cycles));
  weathered.initial_rock = start.initial_rock;
  weathered.final_rock = weathered.rock.count(Material::Rock);
  weathered.colluvium = weathered.rock.count(Material::Colluvium);
  weathered.rock.integrity = RowSpans();  // its memory goes before the VDB and meshes
  // Only a look reads the history: without one, rock.vdb has no history grids (as before looks).
  if (!bake.preset.look) weathered.rock.history = VoxelHistory();
  return weathered;
}

// The stones on LOD0's apron (pipeline/bake_clasts.h), and how many each LOD keeps: their triangles
// come out of the LOD's budget for the rock and colluvium. Gives the LOD chain's targets.
std::vector<double> placeClastsOnApron(Bake& bake, const Weathered& weathered, const MeshStageResult& meshes,
                                       ClastStage& clasts) {
  const Preset& preset = bake.preset;
  if (!preset.clasts) return preset.mesh.lods;
  Stopwatch clock;
  clasts = bakeClasts(weathered.rock, meshes, preset);
  std::vector<double> targets = preset.mesh.lods;
  if (!clasts.set.stones.empty() && exportsFormat(preset, "glb")) {
    const std::vector<std::size_t> budgets =
        lodBudgets(preset, meshes.meshes.rock.triangles.size() + meshes.meshes.colluvium.triangles.size());
    clasts.set.lod_counts = clastLodCounts(clasts.set, budgets);
    for (std::size_t k = 0; k < budgets.size(); ++k)
      targets[k] = double(
          std::max<std::ptrdiff_t>(1, std::ptrdiff_t(budgets[k]) - std::ptrdiff_t(clastTriangles(clasts.set, k + 1))));
  }
  const double seconds = clock.lap();
  spdlog::info("{}: {} of {} stones on the apron, {} stone meshes ({:.1f} s)", preset.name, clasts.set.stones.size(),
               preset.clasts->count, clasts.set.shapes.size(), seconds);
  return targets;
}

// mesh.sink must leave some of the rock above the ground.
void checkSink(const Bake& bake, const VoxelRock& rock) {
  const double sink = sinkDepth(rock, bake.preset.mesh.sink);
  const GridLayout& g = rock.layout;
  int top = -1;
  for (int z = g.nz - 1; z >= 0 && top < 0; --z)
    for (int y = 0; y < g.ny && top < 0; ++y)
      for (int x = 0; x < g.nx; ++x)
        if (rock.material[g.index(x, y, z)] == Material::Rock) {
          top = z;
          break;
        }
  const double height = g.origin[2] + (top + 1) * g.h - footprintPivot(rock)[2];
  if (top >= 0 && sink >= height)
    throw InputError(bake.preset.locate("mesh.sink"), "mesh.sink",
                     fmt::format("sinking the asset {:.4g} deep buries the whole rock, {:.4g} tall", sink, height),
                     "give a depth below the rock's height, or `suggested` for the depth asset.json suggests");
}

// The meshes in memory: LOD0, the stones, the LOD chain and, for a texture set, the bake source
// (pipeline/bake_meshes.h).
std::optional<MeshStageResult> mesh(Bake& bake, const Weathered& weathered, ClastStage& clasts,
                                    PhaseTimes& mesh_times) {
  checkSink(bake, weathered.rock);
  MeshStageResult meshes =
      buildMeshes(weathered.rock, bake.preset, bake.preset.texture.has_value(), &weathered.bubbles);
  Stopwatch clock;
  const std::vector<double> targets = placeClastsOnApron(bake, weathered, meshes, clasts);
  const double clast_seconds = clock.lap();
  addLods(meshes, bake.preset, targets);
  // Side by side with collide(): the times are recorded once both are done.
  mesh_times.add(meshes.times, "mesh_");
  if (bake.preset.clasts) mesh_times.add("clasts", clast_seconds);
  return meshes;
}

// The voxels' collision hulls when export lists collision (collision/collision_hulls.h).
std::optional<CollisionHulls> collide(const Bake& bake, const Weathered& weathered, double& seconds) {
  if (!exportsFormat(bake.preset, "collision")) return std::nullopt;
  Stopwatch clock;
  CollisionHulls hulls = buildCollisionHulls(weathered.rock, bake.preset.collision);
  seconds = clock.lap();
  return hulls;
}

struct Shapes {
  std::optional<MeshStageResult> meshes;
  std::optional<CollisionHulls> hulls;
  ClastStage clasts;  // none without clasts:, ground or colluvium
};

// collision.glb (pipeline/bake_collision.h), around the meshes' pivot, with the stones' hulls when
// collision.colluvium asks for them.
std::optional<AssetCollision> writeCollision(Bake& bake, const Weathered& weathered, Shapes& shapes) {
  if (!shapes.hulls) return std::nullopt;
  Stopwatch clock;
  const auto pivot = footprintPivot(weathered.rock, sinkDepth(weathered.rock, bake.preset.mesh.sink));
  const DeliveryConventions& delivery = bake.delivery;
  CollisionParams params = bake.preset.collision;
  params.naming = delivery.hull_naming;
  AssetCollision collision =
      writeAssetCollision(std::move(*shapes.hulls), params, pivot, bake.dir(), &shapes.clasts.set, delivery.glb);
  shapes.hulls.reset();
  bake.timings.add("collision", clock.lap());
  return collision;
}

// The meshes and the collision hulls, none with --no-mesh. Both read the weathered rock alone, so they are made
// side by side: the hulls take up the cores the mesh stage's serial steps leave idle. Each is the same at any
// thread count, so the files are too.
Shapes meshAndCollide(Bake& bake, const Weathered& weathered) {
  bake.checkCancel();
  Shapes shapes;
  if (!bake.stages.mesh) return shapes;
  bake.startPhase("mesh");
  PhaseTimes mesh_times;
  double collision_seconds = 0.0;
  sideBySide([&] { shapes.meshes = mesh(bake, weathered, shapes.clasts, mesh_times); },
             [&] { shapes.hulls = collide(bake, weathered, collision_seconds); });
  bake.timings.add(mesh_times);
  if (shapes.hulls) bake.timings.add("collision", collision_seconds);
  bake.clock.lap();
  return shapes;
}

// Below this share of a map covered by charts, the bake warns (a house atlas covers 40–70 %).
constexpr double kLeastMapCoverage = 0.10;

// The texture set in OUT/<name>/textures/ (docs/textures.md): every LOD unwrapped, its tangent frames, its maps
// baked from the bake source, which is dropped here, used or not (it is the largest thing the meshes hold).
std::optional<TextureSet> texture(Bake& bake, const Weathered& weathered, std::optional<MeshStageResult>& meshes,
                                  ClastStage& clasts) {
  if (!meshes) return std::nullopt;
  const AssetMeshes source = std::move(meshes->bake_source);
  meshes->bake_source = AssetMeshes{};
  const Preset& preset = bake.preset;
  if (!preset.texture) return std::nullopt;
  bake.checkCancel();
  bake.startPhase("texture");
  TextureSetRequest request;
  request.params = *preset.texture;
  request.seed = preset.seed;
  request.voxel_size = weathered.rock.layout.h;
  request.varied = preset.bake.palette == Palette::Natural;  // the debug and curvature palettes are data
  // The ground plane in the meshes' frame (about the pivot, which mesh.sink raised).
  if (weathered.rock.layout.ground) request.ground = -sinkDepth(weathered.rock, preset.mesh.sink);
  const DeliveryConventions& delivery = bake.delivery;
  request.name = delivery.texture_name;
  request.directx_normals = delivery.directx_normals;
  request.folder = bake.dir() / kTextureFolder;
  // The set takes seconds per LOD at the house sizes: the log follows it LOD by LOD.
  request.progress = [&bake](int lod, int size, int lods_done, int lods) {
    bake.progress("texture", lods_done, std::max(1, lods));
    const double in = bake.since_start.elapsed() + bake.options.load_seconds;
    if (lods_done == 0)
      spdlog::info("{}: texture set: {} LOD{} unwrapped ({:.1f} s in)", bake.preset.name, lods, lods == 1 ? "" : "s",
                   in);
    else
      spdlog::info("{}: texture set: LOD{}'s maps, {} × {} ({} of {}, {:.1f} s in)", bake.preset.name, lod, size, size,
                   lods_done, lods, in);
  };
  std::vector<AssetMeshes> lods{meshes->meshes};
  lods.insert(lods.end(), meshes->lods.begin(), meshes->lods.end());
  TextureSet set;
  try {
    set = bakeTextureSet(lods, source, request);
  } catch (const ChartsDoNotFit& e) {
    throw InputError(preset.locate("texture.padding"), "texture.padding", e.what());
  }
  for (const PhaseTime& step : set.steps.all())
    spdlog::debug("{}: texture set: {} {:.3f} s ({:.3f} CPU-s)", preset.name, step.name, step.seconds,
                  step.cpu_seconds);
  Stopwatch clast_clock;
  textureClasts(clasts, preset, request.folder, delivery.texture_name,
                delivery.directx_normals);  // the stones' own small atlas
  if (!clasts.set.stones.empty()) spdlog::debug("{}: the stones' maps in {:.3f} s", preset.name, clast_clock.elapsed());
  clasts.sources.clear();
  bake.timings.add("texture", bake.clock.lap());
  if (!set.sizes.empty() && set.sizes[0] < lodMapSize(*preset.texture, 0))
    spdlog::info("{}: maps at {} × {}, not texture.size {}: the bake source's {} triangles fill no more", preset.name,
                 set.sizes[0], set.sizes[0], preset.texture->size,
                 source.rock.triangles.size() + source.colluvium.triangles.size());
  // Gutters can take a small map: charts squeezed to a few texels bake nothing an engine can show.
  for (std::size_t k = 0; k < set.coverage.size(); ++k)
    if (set.coverage[k] < kLeastMapCoverage)
      spdlog::warn(
          "{}: LOD{}'s charts cover {:.1f} % of its {} × {} maps ({:.1f} texels per world unit): the gutters "
          "between them (texture.padding {}) take the rest; lower texture.padding or raise texture.size",
          preset.name, k, 100 * set.coverage[k], set.sizes[k], set.sizes[k], set.texels_per_unit[k],
          preset.texture->padding);
  if (set.missed > 0) spdlog::debug("{}: {} texels found no bake source within the cage", preset.name, set.missed);
  return set;
}

// The mesh files, then rock.vdb (its rock_sdf the field the meshes came from); with --no-mesh, rock.vdb
// alone, with the occupancy.
void exportFiles(Bake& bake, const Weathered& weathered, const std::optional<MeshStageResult>& meshes,
                 const std::optional<TextureSet>& textures, const ClastSet& clasts) {
  bake.checkCancel();
  if (!meshes) {
    writeRockVdb(weathered.rock, bake.dir() / "rock.vdb", nullptr, sinkDepth(weathered.rock, bake.preset.mesh.sink));
    bake.timings.add("write_vdb", bake.clock.lap());
    return;
  }
  bake.startPhase("export");
  // Two sets of files from separate data: written side by side.
  double export_seconds = 0.0;
  std::optional<double> vdb_seconds;
  sideBySide(
      [&] {
        export_seconds = exportMeshes(*meshes, textures ? &*textures : nullptr, bake.preset, bake.dir(), &clasts);
      },
      [&] {
        if (!exportsFormat(bake.preset, "vdb")) return;
        Stopwatch clock;
        writeRockVdb(weathered.rock, bake.dir() / "rock.vdb", meshes->rock_sdf.get(),
                     sinkDepth(weathered.rock, bake.preset.mesh.sink));
        vdb_seconds = clock.lap();
      });
  bake.timings.add("export", export_seconds);
  if (vdb_seconds) bake.timings.add("write_vdb", *vdb_seconds);
  bake.clock.lap();
}

// The compressed set (compress/compressed_set.h) from the GLBs just written; asset.json's "sets" (null
// without one).
nlohmann::ordered_json compress(Bake& bake, const std::optional<MeshStageResult>& meshes,
                                const CompressionTools& tools) {
  if (!meshes || !bake.preset.delivery.compressed || !exportsFormat(bake.preset, "glb")) return nullptr;
  bake.checkCancel();
  spdlog::info("{}: the compressed set ({:.1f} s in)", bake.preset.name,
               bake.since_start.elapsed() + bake.options.load_seconds);
  const CompressedSet set = writeCompressedSet(bake.dir(), meshes->lod_files, tools);
  spdlog::info("{}: compressed set in {:.1f} s: {} → {} bytes to download, {} → {} bytes of GPU memory",
               bake.preset.name, set.seconds, set.full.download_bytes, set.compressed.download_bytes,
               set.full.gpuBytes(), set.compressed.gpuBytes());
  bake.timings.add("compress", bake.clock.lap());
  return setsJson(set);
}

void render(Bake& bake, const std::optional<MeshStageResult>& meshes, const std::optional<TextureSet>& textures,
            const ClastSet& clasts) {
  if (!meshes || !bake.stages.render) return;
  bake.checkCancel();
  bake.startPhase("render");
  RenderRequest request;
  request.asset_dir = bake.dir();
  request.params = bake.preset.render;
  request.preset_name = bake.preset.name;
  request.seed = bake.preset.seed;
  request.preset_hash = presetFingerprint(bake.preset, bake.options.manifest);
  request.threads = bake.options.render_threads;
  request.cancel = bake.options.cancel;
  if (textures) {
    const MaterialMaps maps = lodMaterialMaps(*textures, 0);
    request.maps = {maps.base_color};
  }
  if (!clasts.stones.empty()) request.clasts = &clasts;
  const RenderOutputs rendered = renderAsset(textures ? textures->lods.at(0) : meshes->meshes, request);
  bake.timings.add("render", rendered.seconds_total);
  spdlog::info("{}: rendered {} in {:.1f} s", bake.preset.name,
               (bake.asset_dir / rendered.render_png.filename()).string(), rendered.seconds_total);
  if (!rendered.turntable_movie.empty())
    spdlog::info("{}: {} frames, the turntable in {:.1f} s and its movie in {:.2f} s", bake.preset.name,
                 rendered.turntable_frames.size(), rendered.seconds_turntable, rendered.seconds_movie);
  bake.clock.lap();
}

// asset.json, what an asset browser reads (pipeline/asset_json.h): with meshes only; the LODs as shipped (split
// along their UV seams when there is a texture set), the maps and the collision hulls.
void describe(const Bake& bake, const std::optional<MeshStageResult>& meshes, const std::optional<TextureSet>& textures,
              const std::optional<AssetCollision>& collision, const ClastSet& clasts, const VoxelRock& rock,
              const nlohmann::ordered_json& sets) {
  const double h = rock.layout.h;
  if (!meshes) return;
  const Preset& preset = bake.preset;
  AssetDescription asset;
  asset.name = preset.name;
  asset.tags = preset.tags;
  asset.units_per_meter = preset.units_per_meter;
  const DeliveryConventions& delivery = bake.delivery;
  asset.delivery = {{"profile", schema::nameOf(preset.delivery.profile)},
                    {"normal_map", delivery.directx_normals ? "directx" : "opengl"},
                    {"images", delivery.glb.embed_images ? "embedded" : "files"}};
  for (std::size_t i = 0; i <= meshes->lods.size(); ++i) {
    AssetLod lod{meshes->lod_files.at(i), i == 0 ? &meshes->meshes : &meshes->lods[i - 1]};
    if (textures) {
      lod.meshes = &textures->lods.at(i);
      lod.map_size = textures->sizes.at(i);
      lod.texels_per_unit = textures->texels_per_unit.at(i);
    }
    asset.lods.push_back(lod);
  }
  if (textures)
    for (const TextureFile& f : textures->files)
      asset.maps.push_back({mapName(f.map), f.lod, std::string(kTextureFolder) + "/" + f.file, f.size, f.colour_space,
                            f.channels == 1   ? "Y"
                            : f.channels == 3 ? "RGB"
                                              : "RGBA",
                            f.bits});
  asset.preview = bake.stages.render ? "render.png" : "";
  asset.movie = bake.stages.render && preset.render.turntable_frames > 0 ? "turntable.mp4" : "";
  const ManifestInputs& inputs = bake.options.manifest;
  const fs::path base = inputs.base_dir.empty() ? preset.file.parent_path() : inputs.base_dir;
  asset.input_hash = bakeInputHash(preset, bake.stages, base);
  asset.collision = collision;
  asset.individual = individualJson(preset);
  asset.clasts = clastsJson(clasts, h, preset.units_per_meter);
  asset.ground = groundJson(rock, meshes->pivot, sinkDepth(rock, preset.mesh.sink), preset.units_per_meter);
  asset.sets = sets;
  writeAssetJson(asset, bake.dir());
}

void writeStats(Bake& bake, const Weathered& weathered) {
  bake.timings.add("total", bake.clock.elapsed() + bake.options.load_seconds);
  json stats;
  stats["cycles"] = weathered.cycles;
  stats["stages"] = bakeTimingsJson(bake.timings);
  stats["preset"] = presetToJson(bake.preset);
  if (const nlohmann::ordered_json individual = individualJson(bake.preset); !individual.is_null())
    stats["individual"] = individual;
  bake.checkCancel();
  writeFileAtomically(bake.dir() / "stats.json", stats.dump(2) + "\n");
}

// Last of the files: its presence says the folder is complete.
void writeManifestLast(const Bake& bake, const Weathered& weathered) {
  const ManifestStats stats{int(weathered.cycles.size()), weathered.initial_rock, weathered.final_rock,
                            weathered.colluvium};
  writeManifest(bake.before, bake.preset, bake.options.manifest, bake.stages, stats,
                {{"stages", bakeTimingsJson(bake.timings)}});
}

BakeSummary commit(Bake& bake, const Weathered& weathered) {
  bake.staging.commit();
  if (bake.options.progress) bake.options.progress(1.0, "done");
  return {bake.asset_dir,
          int(weathered.cycles.size()),
          weathered.initial_rock,
          weathered.final_rock,
          *bake.timings.seconds("total") - bake.options.load_seconds,
          bake.timings};
}

}  // namespace

Preset presetAsBaked(const Preset& preset, const BakeOptions& options) {
  Preset baked = preset;
  // The switch as given, not applied: a --no-mesh bake keeps its texture: block in the input hash, as
  // libraries baked before recorded it.
  if (!options.stages.textures) baked.texture.reset();
  return baked;
}

BakeSummary bakeAsset(const Preset& preset, const BakeOptions& options) {
  return bakeAsset(preset, readInputs(preset), options);
}

// The recipe. A phase to add is one more line here, a function above, and its row in kBakePhases.
BakeSummary bakeAsset(const Preset& preset, const ResolvedShape& shape, const BakeOptions& options) {
  // A compressor that is missing is said before anything is written.
  const bool compressed = options.stages.applied().mesh && exportsFormat(preset, "glb");
  const CompressionTools compression = compressed ? requireCompressionTools(preset) : CompressionTools{};
  Bake bake(preset, options);
  // A helper program that is missing is said before the simulation, not after it.
  if (options.stages.applied().render) requireHelperPrograms(preset.render.turntable_frames > 0);
  const Weathered weathered = simulate(bake, startSimulation(bake, shape));
  Shapes shapes = meshAndCollide(bake, weathered);
  auto& [meshes, hulls, clasts] = shapes;
  const std::optional<AssetCollision> collision = writeCollision(bake, weathered, shapes);
  const std::optional<TextureSet> textures = texture(bake, weathered, meshes, clasts);
  exportFiles(bake, weathered, meshes, textures, clasts.set);
  const nlohmann::ordered_json sets = compress(bake, meshes, compression);
  render(bake, meshes, textures, clasts.set);
  describe(bake, meshes, textures, collision, clasts.set, weathered.rock, sets);
  writeStats(bake, weathered);
  writeManifestLast(bake, weathered);
  return commit(bake, weathered);
}

}  // namespace rockbake
