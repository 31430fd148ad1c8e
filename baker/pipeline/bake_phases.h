// The phases of a bake, in order (pipeline/bake_asset.cpp, docs/architecture.md): one table
// gives each its name in stats.json's "stages" (and the manifest's "timings.stages"), its
// share of the progress bar and the log line that says it has started. A phase reports
// progress from the sum of the shares before it to that plus its own; "stages" lists the
// timings recorded, in the table's order (README, "What the bake produces"). A new phase is
// a row here.
#pragma once

#include <string_view>

#include <nlohmann/json.hpp>

#include "platform/phase_times.h"

namespace rockbake {

struct BakePhase {
  std::string_view name;   // its key in "stages"
  double progress = 0.0;   // its share of the progress bar; 0: timed only (a part of a phase, or quick)
  std::string_view doing;  // logged when it starts; empty: nothing
};

inline constexpr BakePhase kBakePhases[] = {
    {"load", 0.0, ""},                // the preset and its files, read by the caller
    {"shape", 0.0, ""},               // the initial rock, or the checkpoint's state
    {"simulate", 0.70, ""},           // every cycle, checkpoints written
    {"simulate_curvature", 0.0, ""},  // parts of simulate, summed over the cycles
    {"simulate_colluvium", 0.0, ""},
    {"simulate_rockfall", 0.0, ""},
    {"mesh", 0.05, "meshes and collision hulls"},  // its parts are timed, not the whole
    {"mesh_extract", 0.0, ""},
    {"mesh_subdivide", 0.0, ""},
    {"mesh_attributes", 0.0, ""},
    {"mesh_simplify", 0.0, ""},            // LOD0 and the LODs
    {"clasts", 0.0, ""},                   // the stone meshes and their places on the apron (with clasts:)
    {"texture", 0.05, "the texture set"},  // atlases, tangents, rays, maps and their files
    {"export", 0.05, "writing the meshes and rock.vdb"},  // the mesh files
    {"write_vdb", 0.0, ""},
    {"collision", 0.0, ""},         // the hulls and collision.glb
    {"render", 0.15, "rendering"},  // POV-Ray and its previews
    {"total", 0.0, ""},             // load and every phase
};

// The progress bar's position when `phase` is `within` (0..1) done. Throws std::logic_error
// for a name not in the table.
double bakeProgress(std::string_view phase, double within = 0.0);
const BakePhase& bakePhase(std::string_view name);

// "stages": the recorded times in the table's order. Throws std::logic_error for a recorded
// name that is not in the table, so that a phase cannot be timed without a row.
nlohmann::ordered_json bakeTimingsJson(const PhaseTimes& times);

}  // namespace rockbake
