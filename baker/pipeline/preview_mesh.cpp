#include "pipeline/preview_mesh.h"

#include <vector>

#include "mesh/bake_attributes.h"
#include "mesh/extract_surfaces.h"
#include "sim/weathering.h"

namespace rockbake {

AssetMeshes previewMeshes(const VoxelRock& rock, const Preset& preset, const SimParams& active, Palette palette) {
  AssetMeshes meshes = extractSurfaces(rock, {preset.mesh.smoothing, /*preview=*/true});
  const std::vector<float> exposure = palette == Palette::Curvature ? exposureField(rock, active.bubbles)
                                                                    : std::vector<float>(rock.layout.cellCount(), 0.5f);
  meshes = sampleAttributes(std::move(meshes), {&rock, &exposure});
  PaletteParams params = paletteParams(rock, preset.bake);
  params.palette = palette;
  return applyPalette(std::move(meshes), params);
}

std::uint64_t estimatePreviewBytes(const GridLayout& layout) {
  return (std::uint64_t(64) << 20) + 48 * std::uint64_t(layout.cellCount());
}

}  // namespace rockbake
