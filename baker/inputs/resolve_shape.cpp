#include "inputs/resolve_shape.h"

#include <fmt/format.h>

#include "core/error.h"
#include "core/mesh_checks.h"
#include "inputs/mesh_reader.h"

namespace rockbake {
namespace {

GrayImage readShapeImage(const Preset& preset, const ImageShape& shape) {
  GrayImage image;
  try {
    image = readPngGray(shape.path);
  } catch (const std::exception& e) {
    throw InputError(preset.locate("shape.image.path"), "shape.image.path", e.what(),
                     "give a readable black-and-white PNG; paths are relative to the preset");
  }
  if (image.width <= 0 || image.height <= 0)
    throw InputError(preset.locate("shape.image.path"), "shape.image.path",
                     "the image " + shape.path.string() + " is empty");
  return image;
}

TriangleMesh readBlockout(const Preset& preset, const MeshShape& shape) {
  TriangleMesh mesh;
  try {
    mesh = readTriangleMesh(shape.path);
  } catch (const std::exception& e) {
    throw InputError(preset.locate("shape.mesh.path"), "shape.mesh.path", e.what());
  }
  const std::vector<OpenEdge> open = findOpenEdges(mesh);
  if (!open.empty())
    throw InputError(preset.locate("shape.mesh.path"), "shape.mesh.path",
                     fmt::format("{} is not closed: {} edges are not shared by exactly two consistently "
                                 "oriented faces (e.g. vertices {} and {}, used {} times)",
                                 shape.path.string(), open.size(), open[0].a + 1, open[0].b + 1, open[0].uses),
                     "close the holes and make the normals consistent in the modelling package");
  for (auto& p : mesh.positions)
    for (double& c : p) c *= shape.scale;
  return mesh;
}

}  // namespace

ResolvedShape resolveShape(const Preset& preset) {
  ResolvedShape resolved;
  resolved.params = preset.shape;
  if (const auto* image = std::get_if<ImageShape>(&preset.shape.kind)) resolved.image = readShapeImage(preset, *image);
  if (const auto* blockout = std::get_if<MeshShape>(&preset.shape.kind))
    resolved.mesh = readBlockout(preset, *blockout);
  return resolved;
}

}  // namespace rockbake
