// Colour management through OpenColorIO (SPEC §4) with the project's own
// config, render_templates/ocio/config.ocio: working space scene-linear
// Rec.709, display "sRGB" with view "Standard".
#pragma once

#include <array>
#include <filesystem>

namespace rockbake {

// The source tree's render_templates/ (set at build time); the installed
// layout can override it later.
std::filesystem::path defaultRenderTemplatesDir();
// <templates>/ocio/config.ocio
std::filesystem::path defaultOcioConfig();

// An sRGB-encoded colour (a preset's palette entry, 0..1) to the scene-linear
// working space, through the config's "sRGB - Texture" → scene_linear role.
// Loaded configs and processors are cached; safe from any thread.
std::array<float, 3> srgbToSceneLinear(const std::array<float, 3>& srgb,
                                       const std::filesystem::path& ocio_config = defaultOcioConfig());

// Scene-linear to the default display/view (sRGB, Standard), unclamped.
std::array<float, 3> sceneLinearToDisplay(const std::array<float, 3>& linear,
                                          const std::filesystem::path& ocio_config = defaultOcioConfig());

// Reads an EXR (scene-linear), applies the display/view transform and writes an
// 8-bit RGB PNG atomically. std::runtime_error naming the file on failure.
void exrToPng(const std::filesystem::path& exr, const std::filesystem::path& png,
              const std::filesystem::path& ocio_config = defaultOcioConfig());

}  // namespace rockbake
