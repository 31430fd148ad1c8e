// The preset schema's rules that a table row cannot say (docs/preset-reference.md):
// values with their own reading (altitude graphs, colours, LOD lists, files
// that must exist) and checks between keys (a bubble against the voxel size,
// altitudes that increase, one noise entry per segment). The table in
// preset/schema.cpp names them; each reports through Field, so problems keep
// their file:line:column and key path. Internal to the preset stage.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "preset/schema_spec.h"
#include "preset/schema_values.h"

namespace rockbake::schema {

// Bubble extents in voxels: below one the bubble is the voxel itself and measures nothing; above
// kMaxBubbleVoxels a cycle costs too much.
constexpr double kMaxBubbleVoxels = 48.0;

// ---- values ----
Value<int> schemaVersion();      // `rockbake:`, which must be 1
Value<std::string> assetName();  // [a-z0-9_-]+, at most kMaxNameLength
// A file named relative to the file that gives it, which must exist; `what` names it in problems ("image").
Value<std::filesystem::path> existingFile(std::string what, std::string range);
Value<std::vector<std::array<double, 2>>> altitudePoints();  // [[altitude, durability], ...], altitudes increasing
Value<std::vector<std::array<double, 2>>> responseCurve();   // [[x, y], ...] from x = 0 to x = 1
Value<std::vector<double>> lodList();                        // ratios or triangle counts, decreasing
Value<SrgbColor> color();                                    // "#rrggbb" or [r, g, b]
Value<std::vector<std::string>> exportFormats();             // ply, obj, glb, vdb, collision, each once
Value<std::vector<std::string>> tagList();                   // asset names; repeats dropped
Value<std::string> templateName();                           // a template in render_templates/, by name
Value<int> textureSize();                                    // a power of two, 256 … 8192
Value<std::vector<TextureMap>> textureMaps();                // map names, each once, at least one
// [min, max] with min <= max, each in [lo, hi] (lo excluded when lo_open): a family's ranges.
Value<Interval> interval(double lo, double hi, bool lo_open = false);
Value<std::array<int, 2>> wholeInterval(int lo, int hi);               // [min, max] whole numbers
Value<std::array<Interval, 3>> axisIntervals(double lo, double hi);  // [[min, max] × 3]: x, y, z, each in (lo, hi]

void refuseExtendsOverride(const Field& extends);

// ---- checks (preset/schema_spec.h Check<S>) ----
void oneNoisePerSegment(const Field& graph, const DurabilityGraph& g, const DurabilityGraph*, const ReadContext&);
void wallThinnerThanFootprint(const Field& corner, const InsideCornerShape& c, const InsideCornerShape*,
                              const ReadContext&);
void jitterBelowSpacing(const Field& joint, const JointSet& j, const JointSet*, const ReadContext&);
void widthBelowSpacing(const Field& joint, const JointSet& j, const JointSet*, const ReadContext&);
void keyframeChangesSomething(const Field& keyframe, const DurabilityKeyframe&, const DurabilityKeyframe*,
                              const ReadContext&);
void noiseNeedsPoints(const Field& keyframe, const DurabilityKeyframe&, const DurabilityKeyframe*, const ReadContext&);
void keyframesInTimeOrder(const Field& keyframe, const DurabilityKeyframe& k, const DurabilityKeyframe* previous,
                          const ReadContext&);
void bandsGoUp(const Field& band, const BubbleBand& b, const BubbleBand* previous, const ReadContext&);
void bubbleFitsTheGrid(const Field& band, const BubbleBand& b, const BubbleBand*, const ReadContext& ctx);
void lastBandReachesTheTop(const Field& bands, const std::vector<BubbleBand>& read);
void layersSoftToDurable(const Field& layer, const PaletteLayer& l, const PaletteLayer* previous, const ReadContext&);
// A family needs a shape the fitted grid can place (no shape.center) and joint sets to fracture along.
void familyFitsThePreset(const Field& root, const Preset& p, const Preset*, const ReadContext&);
void timeWithinCycleLimit(const Field& root, const Preset& p, const Preset*, const ReadContext& ctx);

// When a preset gives no bubbles: one band, a sphere of a sixteenth of grid.size's longest side,
// kept within 1 .. kMaxBubbleVoxels voxels.
void defaultBubbles(Preset& p, const ReadContext& ctx);

}  // namespace rockbake::schema
