// The phases of a bake, in order (pipeline/bake_asset.cpp, docs/architecture.md): one table
// gives each its name in stats.json's "stages" (and the manifest's "timings.stages"), its
// stretch of the progress bar and the log line that says it has started. A phase reports
// progress from its start to its start plus its share, and each starts where the one before
// ends (a test checks it; the starts are written out so that they are exact decimals, not
// sums); "stages" lists the timings recorded, in the table's order (README, "What the bake
// produces"). A new phase is a row here.
#pragma once

#include <string_view>

#include <nlohmann/json.hpp>

#include "platform/phase_times.h"

namespace rockbake {

struct BakePhase {
  std::string_view name;   // its key in "stages"
  double start = 0.0;      // where it starts on the progress bar, 0..1
  double share = 0.0;      // its share of the bar; 0: timed only (a part of a phase, or quick)
  std::string_view doing;  // logged when it starts; empty: nothing
};

inline constexpr BakePhase kBakePhases[] = {
    {"load", 0.0, 0.0, ""},                 // the preset and its files, read by the caller
    {"shape", 0.0, 0.0, ""},                // the initial rock, or the checkpoint's state
    {"simulate", 0.0, 0.70, ""},            // every cycle, checkpoints written
    {"simulate_curvature", 0.70, 0.0, ""},  // parts of simulate, summed over the cycles
    {"simulate_colluvium", 0.70, 0.0, ""},
    {"simulate_rockfall", 0.70, 0.0, ""},
    {"simulate_history", 0.70, 0.0, ""},
    {"mesh", 0.70, 0.05, "meshes and collision hulls"},  // its parts are timed, not the whole
    {"mesh_extract", 0.75, 0.0, ""},
    {"mesh_subdivide", 0.75, 0.0, ""},
    {"mesh_attributes", 0.75, 0.0, ""},
    {"mesh_simplify", 0.75, 0.0, ""},            // LOD0 and the LODs
    {"clasts", 0.75, 0.0, ""},                   // the stone meshes and their places on the apron (with clasts:)
    {"texture", 0.75, 0.05, "the texture set"},  // atlases, tangents, rays, maps and their files
    {"export", 0.80, 0.05, "writing the meshes and rock.vdb"},  // the mesh files
    {"write_vdb", 0.85, 0.0, ""},
    {"collision", 0.85, 0.0, ""},         // the hulls and collision.glb
    {"compress", 0.85, 0.0, ""},          // the compressed set (with delivery.compressed)
    {"render", 0.85, 0.15, "rendering"},  // POV-Ray and its previews
    {"total", 1.0, 0.0, ""},              // load and every phase
};

// The progress bar's position when `done` of `of` steps of `phase` are done: start + share ·
// done / of. Throws std::logic_error for a name not in the table.
double bakeProgress(std::string_view phase, double done = 0.0, double of = 1.0);
const BakePhase& bakePhase(std::string_view name);

// "stages": the recorded times in the table's order. Throws std::logic_error for a recorded
// name that is not in the table, so that a phase cannot be timed without a row.
nlohmann::ordered_json bakeTimingsJson(const PhaseTimes& times);

}  // namespace rockbake
