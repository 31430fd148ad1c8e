// `rockbake render ASSET_DIR`: renders a baked asset folder again from what it
// holds (stats.json's resolved preset and rock_mesh.inc), with the same or
// another template, without simulating again, and brings the folder's
// manifest.json up to date (the new renders' sizes and hashes, rerender.template).
#pragma once

#include <filesystem>
#include <string>

#include "render/render_asset.h"

namespace rockbake {

struct RerenderOptions {
  std::filesystem::path asset_dir;
  std::string template_name;  // empty: the template the asset was baked with
  // The still's file name (without .exr / .png), [a-z0-9_-]+; empty: `render` with the asset's own
  // template, `render_<template>` with another, so that a debug view never replaces the bake's render.
  std::string output;
  int threads = 0;  // POV-Ray's threads; 0: all cores
};

// Throws InputError when the folder is not a rendered asset (no stats.json or
// rock_mesh.inc), its stats.json does not parse, or another live process
// holds the asset's lock (pipeline/asset_folder.h), or `output` is not a name.
RenderOutputs rerenderAssetFolder(const RerenderOptions& options);

}  // namespace rockbake
