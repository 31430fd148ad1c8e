// The inputs stage (docs/model.md §8): reads the files a preset's shape names — a
// black-and-white PNG or a closed blockout mesh — once, checks them, and gives
// the simulation a resolved shape value that needs no further I/O.
#pragma once

#include "core/surface_mesh.h"
#include "platform/png_image.h"
#include "preset/preset.h"

namespace rockbake {

struct ResolvedShape {
  ShapeParams params;  // the preset's shape: kind, dimensions (world units), centre
  GrayImage image;     // `image` shapes: the PNG's luminance (white = rock)
  TriangleMesh mesh;   // `mesh` shapes: the blockout, closed and outward, in world units (file units × scale)
};

// Throws InputError at shape.image.path / shape.mesh.path (in the preset's
// file) when the file cannot be read, is empty, or the blockout is not closed.
ResolvedShape resolveShape(const Preset& preset);

}  // namespace rockbake
