// Shared by the collision tests that read collision.glb back with tinygltf.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "collision/collision_hulls.h"

namespace rockbake::test {

inline tinygltf::Model readGlb(const std::filesystem::path& file) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string())) << err;
  return model;
}

template <typename T>
std::vector<T> accessorValues(const tinygltf::Model& model, int index, int components) {
  const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
  const tinygltf::BufferView& v = model.bufferViews[std::size_t(a.bufferView)];
  std::vector<T> values(a.count * std::size_t(components));
  std::memcpy(values.data(), model.buffers[std::size_t(v.buffer)].data.data() + v.byteOffset + a.byteOffset,
              values.size() * sizeof(T));
  return values;
}

struct NamedHull {
  std::string name;  // the node's
  ConvexHull hull;   // z up, about the pivot; volume: what its triangles enclose
};

// Every node of the scene, in order, as a hull back in the asset's z-up frame:
// glTF's (x, y, z) is the asset's (x, −z, y).
inline std::vector<NamedHull> readHulls(const tinygltf::Model& model) {
  std::vector<NamedHull> hulls;
  for (const int n : model.scenes.at(0).nodes) {
    const tinygltf::Node& node = model.nodes.at(std::size_t(n));
    const tinygltf::Primitive& p = model.meshes.at(std::size_t(node.mesh)).primitives.at(0);
    const std::vector<float> xyz = accessorValues<float>(model, p.attributes.at("POSITION"), 3);
    const std::vector<std::uint16_t> corners = accessorValues<std::uint16_t>(model, p.indices, 1);
    NamedHull& h = hulls.emplace_back();
    h.name = node.name;
    for (std::size_t v = 0; v + 2 < xyz.size(); v += 3)
      h.hull.positions.push_back({xyz[v], -double(xyz[v + 2]), xyz[v + 1]});
    for (std::size_t t = 0; t + 2 < corners.size(); t += 3)
      h.hull.triangles.push_back({corners[t], corners[t + 1], corners[t + 2]});
    for (const auto& t : h.hull.triangles) {
      const Vec3d &a = h.hull.positions[t[0]], &b = h.hull.positions[t[1]], &c = h.hull.positions[t[2]];
      h.hull.volume += dot(a, cross(b, c)) / 6.0;
    }
  }
  return hulls;
}

}  // namespace rockbake::test
