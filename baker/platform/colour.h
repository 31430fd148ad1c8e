// Colour, one module for every stage (docs/rendering.md): preset colours are sRGB; scenes,
// meshes and renders work in scene-linear Rec.709. Conversions go through the
// project's OpenColorIO config, render_templates/ocio/config.ocio (working
// space scene-linear Rec.709, display "sRGB" with view "Standard"); the plain
// sRGB transfer function is here too, for files that store sRGB bytes.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace rockbake {

// render_templates/ocio/config.ocio in rockbake's data folder (platform/data_dir.h); throws
// std::runtime_error, saying where it looked, when the data folder lacks it.
std::filesystem::path defaultOcioConfig();

// An sRGB-encoded colour (a preset's palette entry, 0..1) to the scene-linear
// working space, through the config's "sRGB - Texture" → scene_linear role.
// Loaded configs and processors are cached; safe from any thread.
std::array<float, 3> srgbToSceneLinear(const std::array<float, 3>& srgb,
                                       const std::filesystem::path& ocio_config = defaultOcioConfig());

// Scene-linear to the default display/view (sRGB, Standard), unclamped.
std::array<float, 3> sceneLinearToDisplay(const std::array<float, 3>& linear,
                                          const std::filesystem::path& ocio_config = defaultOcioConfig());
// The same for a whole image, in place: `rgb` holds width × height RGB triples.
void sceneLinearToDisplay(std::vector<float>& rgb, int width, int height,
                          const std::filesystem::path& ocio_config = defaultOcioConfig());

// The sRGB transfer function on [0, 1] (input clamped) and its inverse: how
// PLY and OBJ store colours.
float linearToSrgb(float linear);
float srgbToLinear(float srgb);

// The 8-bit sRGB code of a linear value: lround(linearToSrgb(linear) · 255), exactly, found
// among the 255 linear values where the code steps up (a table made once) instead of a power
// per call: a texture set converts millions of texels. NaN gives 0.
std::uint8_t linearToSrgbByte(float linear);

}  // namespace rockbake
