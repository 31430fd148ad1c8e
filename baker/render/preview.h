// Previews of renders (docs/rendering.md): an EXR (scene-linear) through the project's
// OpenColorIO display/view transform (core/colour.h) to an 8-bit sRGB PNG.
#pragma once

#include <filesystem>

#include "core/colour.h"

namespace rockbake {

// The render templates folder: renderTemplatesDir() (preset/render_templates.h).
std::filesystem::path defaultRenderTemplatesDir();

// Reads an EXR (scene-linear), applies the display/view transform and writes an
// 8-bit RGB PNG atomically. std::runtime_error naming the file on failure.
void exrToPng(const std::filesystem::path& exr, const std::filesystem::path& png,
              const std::filesystem::path& ocio_config = defaultOcioConfig());

}  // namespace rockbake
