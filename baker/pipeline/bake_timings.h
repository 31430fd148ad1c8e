// How long each phase of a bake took, in seconds (wall clock): stats.json's
// "stages" and the manifest's "timings.stages" (README, "What the bake
// produces"). bakeTimingsJson writes them in one order; a phase that did not
// run (no meshes, no render, no rock.vdb, no collision.glb) has no entry. A new phase adds a
// field here and a line there.
#pragma once

#include <optional>

#include <nlohmann/json.hpp>

namespace rockbake {

struct MeshTimings {
  double extract = 0.0;
  double subdivide = 0.0;
  double attributes = 0.0;
  double simplify = 0.0;         // LOD0 and the LODs
  std::optional<double> clasts;  // the stone meshes and their places on the apron (with clasts:)
  double exports = 0.0;          // the mesh files
};

struct BakeTimings {
  double load = 0.0;                // the preset and its files, read by the caller
  double shape = 0.0;               // the initial rock, or the checkpoint's state
  double simulate = 0.0;            // every cycle, checkpoints written
  double simulate_curvature = 0.0;  // parts of simulate, summed over the cycles
  double simulate_colluvium = 0.0;
  double simulate_rockfall = 0.0;
  std::optional<MeshTimings> mesh;
  std::optional<double> texture;  // the texture set: atlases, tangents, rays, maps and their files
  std::optional<double> write_vdb;
  std::optional<double> collision;  // the hulls and collision.glb
  std::optional<double> render;     // POV-Ray and its previews
  double total = 0.0;               // load and every phase
};

// {"load", "shape", "simulate", "simulate_curvature", "simulate_colluvium",
//  "simulate_rockfall", "mesh_extract", "mesh_subdivide", "mesh_attributes",
//  "mesh_simplify", "clasts", "texture", "export", "write_vdb", "collision", "render", "total"},
// those that ran.
nlohmann::ordered_json bakeTimingsJson(const BakeTimings& timings);

}  // namespace rockbake
