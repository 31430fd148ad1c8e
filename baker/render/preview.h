// Previews of renders (docs/rendering.md): an EXR (scene-linear) through the project's
// OpenColorIO display/view transform (platform/colour.h) to an 8-bit sRGB PNG.
#pragma once

#include <filesystem>

#include "platform/colour.h"
#include "platform/png_image.h"

namespace rockbake {

// The render templates folder: renderTemplatesDir() (preset/render_templates.h).
std::filesystem::path defaultRenderTemplatesDir();

// Reads an EXR (scene-linear) and applies the display/view transform: 8-bit
// RGB (values clamped to [0, 1], non-finite values black). The look of every
// preview and of the turntable movie. std::runtime_error naming the file on failure.
RgbImage exrToDisplay(const std::filesystem::path& exr, const std::filesystem::path& ocio_config = defaultOcioConfig());

// exrToDisplay written as an 8-bit RGB PNG, atomically.
void exrToPng(const std::filesystem::path& exr, const std::filesystem::path& png,
              const std::filesystem::path& ocio_config = defaultOcioConfig());

}  // namespace rockbake
