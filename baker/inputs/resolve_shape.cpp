#include "inputs/resolve_shape.h"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "geometry/mesh_checks.h"
#include "inputs/mesh_reader.h"

namespace rockbake {
namespace {

GrayImage readShapeImage(const Preset& preset, const ImageShape& shape) {
  GrayImage image;
  try {
    image = readPngGray(shape.path);
  } catch (const std::runtime_error& e) {  // not bad_alloc: running out of memory is not a bad file
    throw InputError(preset.locate("shape.image.path"), "shape.image.path", e.what(),
                     "give a readable black-and-white PNG; paths are relative to the preset");
  }
  if (image.width <= 0 || image.height <= 0)
    throw InputError(preset.locate("shape.image.path"), "shape.image.path",
                     "the image " + shape.path.string() + " is empty");
  return image;
}

// A blockout much wider than tall with the default up axis may be a y-up file lying on its side.
void warnIfLyingOnItsSide(const Preset& preset, const MeshShape& shape, const TriangleMesh& mesh) {
  if (shape.up != UpAxis::Z || preset.locations.count("shape.mesh.up") || mesh.positions.empty()) return;
  Vec3d lo = mesh.positions.front(), hi = lo;
  for (const auto& p : mesh.positions)
    for (std::size_t a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  const double height = hi[2] - lo[2], width = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  if (width > 3 * height)
    spdlog::warn(
        "{}: shape.mesh: the blockout is {:.1f} times wider than tall with z up; if it was written y up "
        "(OBJ and glTF from a DCC, rockbake's own OBJ), say shape.mesh.up: y",
        preset.file.filename().string(), width / std::max(height, 1e-12));
}

TriangleMesh readBlockout(const Preset& preset, const MeshShape& shape) {
  TriangleMesh mesh;
  try {
    mesh = readTriangleMesh(shape.path);
  } catch (const std::runtime_error& e) {  // not bad_alloc: running out of memory is not a bad file
    throw InputError(preset.locate("shape.mesh.path"), "shape.mesh.path", e.what());
  }
  const std::vector<OpenEdge> open = findOpenEdges(mesh);
  if (!open.empty())
    throw InputError(preset.locate("shape.mesh.path"), "shape.mesh.path",
                     fmt::format("{} is not closed: {} edges are not shared by exactly two consistently "
                                 "oriented faces (e.g. vertices {} and {}, used {} times)",
                                 shape.path.string(), open.size(), open[0].a + 1, open[0].b + 1, open[0].uses),
                     "close the holes and make the normals consistent in the modelling package");
  for (auto& p : mesh.positions) {
    for (double& c : p) c *= shape.scale;
    if (shape.up == UpAxis::Y) p = {p[0], -p[2], p[1]};  // a proper rotation: faces keep their orientation
  }
  warnIfLyingOnItsSide(preset, shape, mesh);
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
