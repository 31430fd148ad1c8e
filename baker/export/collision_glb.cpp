#include "export/collision_glb.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "export/glb_file.h"
#include "export/gltf_buffer.h"
#include "platform/atomic_file.h"

namespace rockbake {
namespace {

void addHull(tinygltf::Model& model, const ConvexHull& hull, const Vec3d& pivot, double metres,
             const std::string& name) {
  if (hull.positions.size() > std::numeric_limits<std::uint16_t>::max())
    throw std::runtime_error("hull " + name + " has more vertices than 16-bit indices reach");
  std::vector<float> positions;
  positions.reserve(3 * hull.positions.size());
  tinygltf::Accessor position;
  position.minValues.assign(3, std::numeric_limits<double>::max());
  position.maxValues.assign(3, std::numeric_limits<double>::lowest());
  for (const Vec3d& p : hull.positions) {
    // About the pivot, z-up → y-up, in metres.
    const std::array<float, 3> q{float(metres * (p[0] - pivot[0])), float(metres * (p[2] - pivot[2])),
                                 -float(metres * (p[1] - pivot[1]))};
    positions.insert(positions.end(), q.begin(), q.end());
    for (std::size_t a = 0; a < 3; ++a)
      position.minValues[a] = std::min(position.minValues[a], double(q[a])),
      position.maxValues[a] = std::max(position.maxValues[a], double(q[a]));
  }
  position.bufferView =
      addBufferView(model, positions.data(), positions.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  position.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  position.count = hull.positions.size();
  position.type = TINYGLTF_TYPE_VEC3;
  model.accessors.push_back(position);

  std::vector<std::uint16_t> corners;
  corners.reserve(3 * hull.triangles.size());
  for (const auto& t : hull.triangles)
    for (const std::uint32_t v : t) corners.push_back(std::uint16_t(v));
  tinygltf::Accessor indices;
  indices.bufferView = addBufferView(model, corners.data(), corners.size() * sizeof(std::uint16_t),
                                     TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  indices.count = corners.size();
  indices.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(indices);

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = int(model.accessors.size() - 2);
  primitive.indices = int(model.accessors.size() - 1);
  tinygltf::Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = name;
  node.mesh = int(model.meshes.size() - 1);
  model.nodes.push_back(node);
  model.scenes[0].nodes.push_back(int(model.nodes.size() - 1));
}

}  // namespace

std::string collisionNodeName(HullNaming naming, const std::string& surface, std::size_t index,
                              const std::string& prefix) {
  // Unreal pairs UCX_<name>_<anything> with the mesh <name> of the same import (docs/collision.md).
  const std::string render_mesh = glbMeshName(surface, 0, prefix);
  switch (naming) {
    case HullNaming::Unreal:
      return fmt::format("UCX_{}_{:02}", render_mesh, index);
    case HullNaming::Godot:
      return fmt::format("{}_{:02}-convcolonly", render_mesh, index);
  }
  throw std::logic_error("collisionNodeName: unknown naming");
}

std::string stoneCollisionNodeName(HullNaming naming, std::size_t stone, const std::string& prefix) {
  const std::string render_mesh = glbMeshName("clast_" + std::to_string(stone), -1, prefix);
  switch (naming) {
    case HullNaming::Unreal:
      return fmt::format("UCX_{}_00", render_mesh);
    case HullNaming::Godot:
      return fmt::format("{}_00-convcolonly", render_mesh);
  }
  throw std::logic_error("stoneCollisionNodeName: unknown naming");
}

void writeCollisionGlb(const CollisionHulls& hulls, const Vec3d& pivot, HullNaming naming,
                       const std::filesystem::path& file, const GlbConventions& conventions) {
  const double metres = conventions.meters_per_unit;
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "rockbake " ROCKBAKE_VERSION;
  model.buffers.resize(1);
  model.scenes.resize(1);
  model.scenes[0].name = "collision";  // also keeps an empty scene an object when written
  model.defaultScene = 0;
  try {
    for (const auto& [surface, list] : {std::pair{"rock", &hulls.rock}, std::pair{"colluvium", &hulls.colluvium}})
      for (std::size_t i = 0; i < list->size(); ++i)
        addHull(model, (*list)[i], pivot, metres, collisionNodeName(naming, surface, i, conventions.mesh_prefix));
    for (std::size_t k = 0; k < hulls.stones.size(); ++k)
      addHull(model, hulls.stones[k], pivot, metres, stoneCollisionNodeName(naming, k, conventions.mesh_prefix));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
  if (model.buffers[0].data.empty()) model.buffers.clear();  // glTF forbids an empty buffer
  writeFileAtomically(file, [&](std::ostream& os) {
    tinygltf::TinyGLTF gltf;
    if (!gltf.WriteGltfSceneToStream(&model, os, false, true))
      throw std::runtime_error(file.string() + ": tinygltf could not write the scene");
  });
}

}  // namespace rockbake
