// rock.vdb's rock_sdf after the mesh stage (docs/meshes.md): the smoothed field the
// rock surface was extracted from, not the raw occupancy.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "geometry/mesh_checks.h"
#include "platform/openvdb_support.h"
#include "inputs/mesh_reader.h"
#include "inputs/resolve_shape.h"
#include "mesh/extract_surfaces.h"
#include "pipeline/bake_asset.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

openvdb::FloatGrid::Ptr readSdf(const fs::path& file) {
  openvdb::initialize();
  openvdb::io::File vdb(file.string());
  vdb.open(false);
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(vdb.readGrid("rock_sdf"));
  vdb.close();
  return grid;
}

struct FieldError {
  double mean = 0, max = 0;  // |phi| at the mesh's vertices, in voxels
};

// `Mesh`: a TriangleMesh read back from a file, or a SurfaceMesh in memory.
template <typename Mesh>
FieldError fieldAtVertices(const openvdb::FloatGrid& sdf, const Mesh& mesh, double h) {
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(sdf);
  FieldError e;
  for (const auto& p : mesh.positions) {
    const double phi = std::abs(sampler.wsSample(openvdb::Vec3R(p[0], p[1], p[2]))) / h;
    e.mean += phi / double(mesh.positions.size());
    e.max = std::max(e.max, phi);
  }
  return e;
}

// A 2.4-unit box on the ground of a 4 x 4 x 3 domain, weathered for `cycles`.
Preset boxOnTheGround(int resolution, int cycles) {
  Preset p = test::cubePreset(3.0, 30, 0.3);
  p.grid.size = {4.0, 4.0, 3.0};
  p.grid.resolution = resolution;
  p.grid.ground = true;
  p.shape.kind = BoxShape{{2.4, 2.4, 2.4}};
  p.shape.center.reset();
  p.stop.cycles = cycles;
  return p;
}

TEST(MeshSdf, RockVdbCarriesTheFieldTheMeshWasExtractedFrom) {
  // A weathered box on the ground, smoothed twice: the smoothed surface sits
  // well away from the voxel faces at edges and corners.
  Preset p = boxOnTheGround(40, 6);
  p.name = "sdf";
  p.mesh.smoothing = 2.0;
  p.mesh.subdivision = 0;   // the exported vertices are the extracted ones
  p.mesh.max_error = 1e-4;  // LOD0 keeps (nearly) all of them
  p.mesh.lods.clear();
  p.exports = {"ply", "vdb"};
  const double h = 4.0 / 40;

  test::TempDir meshed, bare;
  BakeOptions options;
  options.stages.render = false;
  options.out_dir = meshed.path();
  bakeAsset(p, options);
  options.out_dir = bare.path();
  options.stages.mesh = false;
  bakeAsset(p, options);

  const TriangleMesh surface = readTriangleMesh(meshed.path() / "sdf" / "rock.ply");
  ASSERT_GT(surface.positions.size(), 1000u);
  const auto smoothed = readSdf(meshed.path() / "sdf" / "rock.vdb");
  const auto occupancy = readSdf(bare.path() / "sdf" / "rock.vdb");
  ASSERT_TRUE(smoothed && occupancy);
  EXPECT_EQ(smoothed->getGridClass(), openvdb::GRID_LEVEL_SET);
  EXPECT_DOUBLE_EQ(smoothed->voxelSize()[0], h);
  // Voxel centres: index (0, 0, 0) sits half a voxel inside the domain's corner.
  EXPECT_TRUE(smoothed->transform() == occupancy->transform());

  // The mesh lies on the zero crossing of the field in the file ...
  const FieldError on_field = fieldAtVertices(*smoothed, surface, h);
  EXPECT_LT(on_field.mean, 0.05) << "voxels";
  EXPECT_LT(on_field.max, 0.3) << "voxels";
  // ... and not on that of the raw occupancy, which --no-mesh writes.
  const FieldError on_occupancy = fieldAtVertices(*occupancy, surface, h);
  EXPECT_GT(on_occupancy.mean, 3 * on_field.mean + 0.02) << "voxels";
}

// The studio's cheaper preview extraction (ExtractParams::preview) stays
// within half a voxel of the bake's surface (a fiftieth on average), closed,
// on a weathered rock.
TEST(MeshSdf, PreviewExtractionFollowsTheBakesSurface) {
  const Preset p = boxOnTheGround(48, 10);
  const VoxelRock rock = weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
  const double h = rock.layout.h;
  for (double smoothing : {1.0, 2.0}) {
    std::shared_ptr<const SmoothedSdf> bake_field;
    const AssetMeshes bake = extractSurfaces(rock, {smoothing, false}, &bake_field);
    const AssetMeshes preview = extractSurfaces(rock, {smoothing, true});
    ASSERT_TRUE(bake_field);
    EXPECT_TRUE(findOpenEdges(preview.rock).empty()) << "smoothing " << smoothing;
    const FieldError e = fieldAtVertices(*bake_field->grid, preview.rock, h);
    EXPECT_LT(e.mean, 0.05) << "smoothing " << smoothing;
    EXPECT_LT(e.max, 0.5) << "smoothing " << smoothing;
    std::printf("preview against bake, smoothing %.0f: mean %.3f, max %.3f voxels\n", smoothing, e.mean, e.max);
  }
}

}  // namespace
}  // namespace rockbake
