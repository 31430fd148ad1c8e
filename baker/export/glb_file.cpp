#include "export/glb_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

#include <tiny_gltf.h>

#include "export/gltf_buffer.h"
#include "platform/atomic_file.h"
#include "platform/png_image.h"

namespace rockbake {
namespace {

int addFloatAccessor(tinygltf::Model& model, const std::vector<float>& values, int components, bool bounds) {
  tinygltf::Accessor a;
  a.bufferView = addBufferView(model, values.data(), values.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = values.size() / std::size_t(components);
  a.type = components == 1   ? TINYGLTF_TYPE_SCALAR
           : components == 2 ? TINYGLTF_TYPE_VEC2
           : components == 4 ? TINYGLTF_TYPE_VEC4
                             : TINYGLTF_TYPE_VEC3;
  if (bounds) {
    a.minValues.assign(std::size_t(components), std::numeric_limits<double>::max());
    a.maxValues.assign(std::size_t(components), std::numeric_limits<double>::lowest());
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::size_t c = i % std::size_t(components);
      a.minValues[c] = std::min(a.minValues[c], double(values[i]));
      a.maxValues[c] = std::max(a.maxValues[c], double(values[i]));
    }
  }
  model.accessors.push_back(a);
  return int(model.accessors.size() - 1);
}

// Values in [0, 1] as unsigned integers read back normalised (glTF 2.0 §3.11: COLOR_n and
// TEXCOORD_n may be normalised unsigned bytes or shorts; custom attributes anything): `Unsigned`
// std::uint8_t for data an 8-bit map holds as well (the mask, the look), std::uint16_t for uvs,
// within 1/65535 (a thirtieth of a texel at 2048). Each element stays 4-byte aligned as glTF
// requires of vertex attributes: VEC4 bytes, VEC2 shorts.
template <typename Unsigned>
int addNormalisedAccessor(tinygltf::Model& model, const std::vector<float>& values, int components) {
  constexpr float kMax = float(std::numeric_limits<Unsigned>::max());
  std::vector<Unsigned> stored(values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    stored[i] = Unsigned(std::lround(std::clamp(values[i], 0.0f, 1.0f) * kMax));
  tinygltf::Accessor a;
  a.bufferView = addBufferView(model, stored.data(), stored.size() * sizeof(Unsigned), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType =
      sizeof(Unsigned) == 1 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE : TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  a.normalized = true;
  a.count = values.size() / std::size_t(components);
  a.type = components == 2 ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC4;
  model.accessors.push_back(a);
  return int(model.accessors.size() - 1);
}

// The texture set's images, each once, and a texture for each (trilinear, clamped: an atlas's
// charts end in gutters, not in a repeat). Returns the texture index per map, -1 where none.
struct MapTextures {
  int base_color = -1, normal = -1, orm = -1;
};
// The bytes of the map at `uri` (relative to `folder`), to embed; a DirectX normal map
// (`directx_normal`) with its green turned back to glTF's convention.
std::string embeddedMap(const std::filesystem::path& folder, const std::string& uri, bool directx_normal) {
  if (directx_normal) {
    RgbImage map = readPngRgb(folder / uri);
    for (std::size_t i = 1; i < map.pixels.size(); i += 3) map.pixels[i] = std::uint8_t(255 - map.pixels[i]);
    return encodePngRgb(map);
  }
  std::ifstream in(folder / uri, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty() || (!in.good() && !in.eof()))
    throw std::runtime_error("cannot read the map " + (folder / uri).string() + " to embed it");
  return bytes;
}

MapTextures addMapTextures(tinygltf::Model& model, const MaterialMaps& maps, const GlbConventions& conventions) {
  MapTextures t;
  if (maps.base_color.empty() && maps.normal.empty() && maps.orm.empty()) return t;
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  sampler.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  model.samplers.push_back(sampler);
  const auto add = [&](const std::string& uri, bool normal) {
    if (uri.empty()) return -1;
    tinygltf::Image image;
    image.mimeType = "image/png";
    const bool directx = normal && conventions.directx_normal_files;
    if (conventions.embed_images) {
      const std::string bytes = embeddedMap(conventions.image_folder, uri, directx);
      image.bufferView = addBufferView(model, bytes.data(), bytes.size(), 0);
      image.name = std::filesystem::path(uri).stem().string();
    } else if (directx) {
      throw std::logic_error("writeGlb: a DirectX normal map cannot be named by URI");
    } else {
      image.uri = uri;
    }
    model.images.push_back(image);
    tinygltf::Texture texture;
    texture.source = int(model.images.size() - 1);
    texture.sampler = int(model.samplers.size() - 1);
    model.textures.push_back(texture);
    return int(model.textures.size() - 1);
  };
  t.base_color = add(maps.base_color, false);
  t.normal = add(maps.normal, true);
  t.orm = add(maps.orm, false);
  return t;
}

// The primitive of `m` with its material (named after the mesh), in `model`.
// The triangles' indices, in 16 bits where the vertices allow (every LOD but a hero's LOD0), else 32.
int addIndexAccessor(tinygltf::Model& model, const SurfaceMesh& m) {
  tinygltf::Accessor indices;
  if (m.positions.size() <= std::numeric_limits<std::uint16_t>::max()) {
    std::vector<std::uint16_t> narrow;
    narrow.reserve(3 * m.triangles.size());
    for (const auto& t : m.triangles)
      for (std::uint32_t v : t) narrow.push_back(std::uint16_t(v));
    indices.bufferView = addBufferView(model, narrow.data(), narrow.size() * sizeof(std::uint16_t),
                                       TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  } else {
    indices.bufferView = addBufferView(model, m.triangles.data(), m.triangles.size() * sizeof(m.triangles[0]),
                                       TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  }
  indices.count = 3 * m.triangles.size();
  indices.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(indices);
  return int(model.accessors.size() - 1);
}

tinygltf::Primitive addPrimitive(tinygltf::Model& model, const SurfaceMesh& m,
                                 const std::array<float, 2>& durability_range, const MapTextures& maps,
                                 const GlbConventions& conventions) {
  const std::size_t n = m.positions.size();
  if (m.normals.size() != n || m.colors.size() != n || m.durability.size() != n || m.colluvium.size() != n ||
      m.curvature.size() != n || m.altitude.size() != n || !m.quads.empty())
    throw std::runtime_error("the " + m.name + " mesh lacks normals, colours or attributes, or has quads");
  const bool textured = maps.base_color >= 0 || maps.normal >= 0 || maps.orm >= 0;
  // A LOD the texture set unwrapped carries its atlas whichever maps were made: the mask and the
  // height map (which no glTF material names) are read through TEXCOORD_0 too.
  const bool unwrapped = n > 0 && m.uvs.size() == n && m.tangents.size() == n;
  if (textured && !unwrapped) throw std::runtime_error("the " + m.name + " mesh has maps but no uvs or tangents");
  std::vector<float> positions, normals, colors, mask;
  positions.reserve(3 * n), normals.reserve(3 * n), colors.reserve(3 * n), mask.reserve(4 * n);
  const float d_lo = durability_range[0], d_span = durability_range[1] - durability_range[0];
  const auto unit = [](float v) { return std::clamp(v, 0.0f, 1.0f); };
  const auto metres = float(conventions.meters_per_unit);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = m.positions[i];
    const auto& q = m.normals[i];
    positions.insert(positions.end(), {metres * p[0], metres * p[2], -metres * p[1]});  // z-up → y-up
    normals.insert(normals.end(), {q[0], q[2], -q[1]});
    // With a base-colour map COLOR_0 is white (below): glTF multiplies it into the map, and it
    // must be there for COLOR_1 (the mask) to be a valid set.
    if (maps.base_color < 0) colors.insert(colors.end(), m.colors[i].begin(), m.colors[i].end());
    // The packed mask every DCC reads as a second colour set.
    const float durability = m.durability[i] <= 0.0f ? 0.0f : d_span > 0 ? (m.durability[i] - d_lo) / d_span : 0.5f;
    mask.insert(mask.end(), {unit(durability), unit(m.colluvium[i]), unit(m.curvature[i]), unit(m.altitude[i])});
  }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = addFloatAccessor(model, positions, 3, true);
  prim.attributes["NORMAL"] = addFloatAccessor(model, normals, 3, false);
  if (unwrapped) {
    std::vector<float> uvs, tangents;
    uvs.reserve(2 * n), tangents.reserve(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& t = m.tangents[i];
      uvs.insert(uvs.end(), m.uvs[i].begin(), m.uvs[i].end());
      // The same rotation as the normals; a rotation keeps the frame's handedness, so w stays.
      tangents.insert(tangents.end(), {t[0], t[2], -t[1], t[3]});
    }
    prim.attributes["TEXCOORD_0"] = addNormalisedAccessor<std::uint16_t>(model, uvs, 2);
    prim.attributes["TANGENT"] = addFloatAccessor(model, tangents, 4, false);
  }
  // White is exact in normalised bytes, a third of the floats' size; colours stay floats.
  prim.attributes["COLOR_0"] = maps.base_color >= 0
                                   ? addNormalisedAccessor<std::uint8_t>(model, std::vector<float>(4 * n, 1.0f), 4)
                                   : addFloatAccessor(model, colors, 3, false);
  prim.attributes["COLOR_1"] = addNormalisedAccessor<std::uint8_t>(model, mask, 4);
  prim.attributes["_DURABILITY"] = addFloatAccessor(model, m.durability, 1, false);
  prim.attributes["_COLLUVIUM"] = addFloatAccessor(model, m.colluvium, 1, false);
  prim.attributes["_CURVATURE"] = addFloatAccessor(model, m.curvature, 1, false);
  prim.attributes["_ALTITUDE"] = addFloatAccessor(model, m.altitude, 1, false);
  // The look (mesh/surface_look.h), where the bake has one: the History map's RGBA per vertex.
  if (m.look.size() == n && n > 0) {
    std::vector<float> look;
    look.reserve(4 * n);
    for (const auto& v : m.look) look.insert(look.end(), v.begin(), v.end());
    prim.attributes["_HISTORY"] = addNormalisedAccessor<std::uint8_t>(model, look, 4);
  }
  if (m.history.size() == n && n > 0) {
    std::vector<float> scar;
    scar.reserve(n);
    for (const auto& v : m.history) scar.push_back(v[1]);
    prim.attributes["_SCAR"] = addFloatAccessor(model, scar, 1, false);
  }

  prim.indices = addIndexAccessor(model, m);

  tinygltf::Material material;
  material.name = conventions.material_prefix + m.name;
  material.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  if (maps.orm >= 0) {
    // The map holds both: factors of 1 read it as it is (its B, metal, is 0).
    material.pbrMetallicRoughness.metallicRoughnessTexture.index = maps.orm;
    material.occlusionTexture.index = maps.orm;
  } else {
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.9;
  }
  if (maps.base_color >= 0) material.pbrMetallicRoughness.baseColorTexture.index = maps.base_color;
  if (maps.normal >= 0) material.normalTexture.index = maps.normal;
  model.materials.push_back(material);
  prim.material = int(model.materials.size() - 1);
  return prim;
}

void addSurface(tinygltf::Model& model, const SurfaceMesh& m, const std::array<float, 2>& durability_range, int lod,
                const MapTextures& maps, const GlbConventions& conventions) {
  const tinygltf::Primitive prim = addPrimitive(model, m, durability_range, maps, conventions);
  const std::string name = glbMeshName(m.name, lod, conventions.mesh_prefix);
  tinygltf::Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = name;
  node.mesh = int(model.meshes.size() - 1);
  model.nodes.push_back(node);
  model.scenes[0].nodes.push_back(int(model.nodes.size() - 1));
}

// The stones LOD `lod` keeps: one mesh per shape they use (sharing one material), one node each.
void addClasts(tinygltf::Model& model, const ClastSet& set, const std::array<float, 2>& durability_range, int lod,
               const GlbConventions& conventions) {
  const std::size_t count = set.lod_counts.empty() ? set.stones.size() : set.lod_counts.at(std::size_t(lod));
  if (count == 0) return;
  const auto uri = [](const std::string& file) { return file.empty() ? file : "textures/" + file; };
  const MapTextures maps = addMapTextures(model, {uri(set.base_color), uri(set.normal), uri(set.orm), ""}, conventions);
  std::vector<int> mesh_of(set.shapes.size(), -1);
  int material = -1;
  for (std::size_t k = 0; k < count; ++k) {
    const ClastInstance& stone = set.stones[k];
    int& mesh = mesh_of.at(std::size_t(stone.shape));
    if (mesh < 0) {
      tinygltf::Primitive prim;
      if (material < 0) {
        prim = addPrimitive(model, set.shapes[std::size_t(stone.shape)], durability_range, maps, conventions);
        material = prim.material;
      } else {
        // One material for every stone mesh: drop the copy addPrimitive made.
        prim = addPrimitive(model, set.shapes[std::size_t(stone.shape)], durability_range, maps, conventions);
        model.materials.pop_back();
        prim.material = material;
      }
      tinygltf::Mesh m;
      m.name = glbMeshName("clast_shape_" + std::to_string(stone.shape), -1, conventions.mesh_prefix);
      m.primitives.push_back(prim);
      model.meshes.push_back(m);
      mesh = int(model.meshes.size() - 1);
    }
    tinygltf::Node node;
    node.name = glbMeshName("clast_" + std::to_string(k), -1, conventions.mesh_prefix);
    node.mesh = mesh;
    const auto& t = stone.translation;
    const auto& q = stone.rotation;
    const double metres = conventions.meters_per_unit;
    node.translation = {metres * t[0], metres * t[2], -metres * t[1]};  // z-up → y-up, as the vertices
    // The same change of frame on the rotation: (x, y, z) → (x, z, −y) turns the axis alike.
    node.rotation = {q[0], q[2], -q[1], q[3]};
    node.scale = {metres * stone.scale, metres * stone.scale, metres * stone.scale};
    model.nodes.push_back(node);
    model.scenes[0].nodes.push_back(int(model.nodes.size() - 1));
  }
}

}  // namespace

std::string glbMeshName(const std::string& surface, int lod, const std::string& prefix) {
  return prefix + surface + (lod >= 0 ? "_lod" + std::to_string(lod) : std::string());
}

void writeGlb(const AssetMeshes& meshes, const std::filesystem::path& file, int lod, const MaterialMaps& maps,
              const ClastSet* clasts, const GlbConventions& conventions) {
  if (!(conventions.meters_per_unit > 0)) throw std::logic_error("writeGlb: meters_per_unit must be > 0");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "rockbake " ROCKBAKE_VERSION;
  model.buffers.resize(1);
  model.scenes.resize(1);
  model.defaultScene = 0;
  try {
    const MapTextures textures = addMapTextures(model, maps, conventions);
    for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium})
      if (!m->positions.empty()) addSurface(model, *m, meshes.durability_range, lod, textures, conventions);
    if (clasts) addClasts(model, *clasts, meshes.durability_range, lod, conventions);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
  writeFileAtomically(file, [&](std::ostream& os) {
    tinygltf::TinyGLTF gltf;
    gltf.SetImageWriter(nullptr, nullptr);  // images stay files beside the GLB, named by their URIs
    if (!gltf.WriteGltfSceneToStream(&model, os, false, true))
      throw std::runtime_error(file.string() + ": tinygltf could not write the scene");
  });
}

}  // namespace rockbake
