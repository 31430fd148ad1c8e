// What the exports and the render include make of a textured LOD (docs/formats.md, docs/rendering.md):
// the GLB's TEXCOORD_0, TANGENT and material, the OBJ's vt and MTL, the POV-Ray include's uv_vectors
// and mapped texture.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "export/glb_file.h"
#include "export/obj_file.h"
#include "render/scene.h"
#include "test_support.h"
#include "texture/tangents.h"
#include "texture/uv_atlas.h"
#include "texture_fixtures.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

// A sphere as the texture stage leaves a LOD: split along its seams, with uvs and tangents.
AssetMeshes texturedSphere() {
  AssetMeshes m = buildUvAtlas(test::assetOf(test::sphereSurface(2)), 256, 4).meshes;
  computeTangents(m.rock);
  return m;
}

const MaterialMaps kMaps{"textures/s_BaseColor.png", "textures/s_Normal_LOD0.png", "textures/s_ORM.png",
                         "textures/s_Height.exr"};

template <class T>
std::vector<T> accessorValues(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors.at(std::size_t(index));
  const tinygltf::BufferView& v = model.bufferViews.at(std::size_t(a.bufferView));
  const int components = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
  std::vector<T> values(a.count * std::size_t(components));
  std::memcpy(values.data(), model.buffers[0].data.data() + v.byteOffset + a.byteOffset, values.size() * sizeof(T));
  return values;
}

TEST(TexturedExports, GlbCarriesUvsTheBakersTangentsAndTheMaps) {
  test::TempDir dir;
  const AssetMeshes m = texturedSphere();
  writeGlb(m, dir.path() / "rock.glb", 0, kMaps);
  fs::create_directories(dir.path() / "textures");
  for (const std::string& uri : {kMaps.base_color, kMaps.normal, kMaps.orm}) test::writeText(dir.path() / uri, "png");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  // The images stay files beside the GLB: do not load them here, only their URIs matter.
  loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                           void*) { return true; },
                        nullptr);
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (dir.path() / "rock.glb").string())) << err;
  ASSERT_EQ(model.meshes.size(), 1u);
  const tinygltf::Primitive& prim = model.meshes[0].primitives[0];
  // The uvs in normalised 16 bits, as glTF allows (the writer's choice: a thirtieth of a texel at 2048).
  const tinygltf::Accessor& uv_accessor = model.accessors.at(std::size_t(prim.attributes.at("TEXCOORD_0")));
  EXPECT_EQ(uv_accessor.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  EXPECT_TRUE(uv_accessor.normalized);
  const auto uvs = accessorValues<std::uint16_t>(model, prim.attributes.at("TEXCOORD_0"));
  const auto tangents = accessorValues<float>(model, prim.attributes.at("TANGENT"));
  // COLOR_0 multiplies the base colour map: white, as normalised bytes (exact).
  const tinygltf::Accessor& colour_accessor = model.accessors.at(std::size_t(prim.attributes.at("COLOR_0")));
  EXPECT_EQ(colour_accessor.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
  EXPECT_TRUE(colour_accessor.normalized);
  EXPECT_EQ(colour_accessor.type, TINYGLTF_TYPE_VEC4);
  const auto colours = accessorValues<std::uint8_t>(model, prim.attributes.at("COLOR_0"));
  const std::size_t n = m.rock.positions.size();
  ASSERT_EQ(uvs.size(), 2 * n);
  ASSERT_EQ(tangents.size(), 4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_NEAR(uvs[2 * i] / 65535.0, m.rock.uvs[i][0], 0.5 / 65535 + 1e-7);
    ASSERT_NEAR(uvs[2 * i + 1] / 65535.0, m.rock.uvs[i][1], 0.5 / 65535 + 1e-7);
    // The frames the maps were baked in, in glTF's y-up axes (x, z, -y), handedness in w.
    const auto& t = m.rock.tangents[i];
    ASSERT_EQ(tangents[4 * i], t[0]);
    ASSERT_EQ(tangents[4 * i + 1], t[2]);
    ASSERT_EQ(tangents[4 * i + 2], -t[1]);
    ASSERT_EQ(tangents[4 * i + 3], t[3]);
    ASSERT_TRUE(t[3] == 1.0f || t[3] == -1.0f);
    for (int c = 0; c < 4; ++c) ASSERT_EQ(colours[4 * i + std::size_t(c)], 255);
  }
  // One material, its maps by relative URI; the ORM image serves occlusion and metal-roughness.
  ASSERT_EQ(model.materials.size(), 1u);
  const tinygltf::Material& mat = model.materials[0];
  const auto uri = [&](int texture) {
    return model.images.at(std::size_t(model.textures.at(std::size_t(texture)).source)).uri;
  };
  EXPECT_EQ(uri(mat.pbrMetallicRoughness.baseColorTexture.index), kMaps.base_color);
  EXPECT_EQ(uri(mat.normalTexture.index), kMaps.normal);
  EXPECT_EQ(uri(mat.occlusionTexture.index), kMaps.orm);
  EXPECT_EQ(uri(mat.pbrMetallicRoughness.metallicRoughnessTexture.index), kMaps.orm);
  EXPECT_EQ(mat.pbrMetallicRoughness.metallicFactor, 1.0);
  EXPECT_EQ(model.images.size(), 3u);  // the height is not a glTF map
  for (const tinygltf::Image& image : model.images) EXPECT_TRUE(image.image.empty()) << image.uri;

  // Maps without uvs are refused, naming the file.
  AssetMeshes bare = test::assetOf(test::sphereSurface(1));
  try {
    writeGlb(bare, dir.path() / "bare.glb", 0, kMaps);
    FAIL() << "a mesh without uvs was written with maps";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bare.glb"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir.path() / "bare.glb"));
}

TEST(TexturedExports, ObjFacesCarryTheirUvsAndTheMtlNamesTheMaps) {
  test::TempDir dir;
  const AssetMeshes split = texturedSphere();
  // The welded LOD the split one came from: the same triangles in the same order.
  const AssetMeshes welded = test::assetOf(test::sphereSurface(2));
  writeObj(welded, dir.path() / "rock.obj", &split, kMaps);
  const std::string obj = test::readBytes(dir.path() / "rock.obj"), mtl = test::readBytes(dir.path() / "rock.mtl");
  std::size_t v = 0, vt = 0, f = 0;
  std::istringstream lines(obj);
  std::string line;
  std::vector<std::array<float, 2>> uv;
  while (std::getline(lines, line)) {
    if (line.rfind("v ", 0) == 0) ++v;
    if (line.rfind("vt ", 0) == 0) {
      float a = 0, b = 0;
      std::sscanf(line.c_str(), "vt %f %f", &a, &b);
      uv.push_back({a, b});
      ++vt;
    }
    if (line.rfind("f ", 0) == 0) {
      unsigned p[3], t[3], n[3];
      ASSERT_EQ(std::sscanf(line.c_str(), "f %u/%u/%u %u/%u/%u %u/%u/%u", &p[0], &t[0], &n[0], &p[1], &t[1], &n[1],
                            &p[2], &t[2], &n[2]),
                9)
          << line;
      // Positions from the welded surface, uvs from the split one's corner (OBJ's v runs up).
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(p[k] - 1, welded.rock.triangles[f][std::size_t(k)]);
        ASSERT_EQ(p[k], n[k]);
        const auto& expected = split.rock.uvs[split.rock.triangles[f][std::size_t(k)]];
        ASSERT_NEAR(uv.at(t[k] - 1)[0], expected[0], 1e-6);
        ASSERT_NEAR(uv.at(t[k] - 1)[1], 1.0f - expected[1], 1e-6);
      }
      ++f;
    }
  }
  EXPECT_EQ(v, welded.rock.positions.size());  // the surface stays welded: seams are in vt only
  EXPECT_EQ(vt, split.rock.positions.size());
  EXPECT_EQ(f, welded.rock.triangles.size());
  for (const char* want : {"map_Kd textures/s_BaseColor.png", "norm textures/s_Normal_LOD0.png",
                           "map_Bump -bm 1 textures/s_Normal_LOD0.png", "disp textures/s_Height.exr"})
    EXPECT_NE(mtl.find(want), std::string::npos) << want << " in\n" << mtl;

  // A split mesh that does not match the welded one triangle for triangle is refused.
  const AssetMeshes other = test::assetOf(test::sphereSurface(1));
  EXPECT_THROW(writeObj(other, dir.path() / "other.obj", &split, kMaps), std::runtime_error);
}

TEST(TexturedExports, RenderIncludeMapsTheBaseColour) {
  test::TempDir dir;
  const AssetMeshes m = texturedSphere();
  writeMeshInclude(m, dir.path() / "rock_mesh.inc", {"textures/s_BaseColor.png"});
  const std::string inc = test::readBytes(dir.path() / "rock_mesh.inc");
  EXPECT_NE(inc.find("uv_vectors { " + std::to_string(m.rock.positions.size())), std::string::npos);
  // The sRGB PNG decoded to linear light for the assumed_gamma 1.0 scene; no image bump (RenderMaps).
  EXPECT_NE(inc.find("image_map { png \"textures/s_BaseColor.png\" gamma srgb"), std::string::npos)
      << inc.substr(0, 600);
  EXPECT_EQ(inc.find("bump_map"), std::string::npos);
  // Templates choose: only with Rockbake_Use_Maps set do the maps replace the vertex colours.
  EXPECT_NE(inc.find("#ifndef (Rockbake_Use_Maps)\n#declare Rockbake_Use_Maps = 0;"), std::string::npos);
  EXPECT_NE(inc.find("#if (Rockbake_Use_Maps)"), std::string::npos);
  EXPECT_NE(inc.find("texture_list"), std::string::npos);

  // Without maps, no uvs and no switch.
  writeMeshInclude(m, dir.path() / "plain.inc");
  const std::string plain = test::readBytes(dir.path() / "plain.inc");
  EXPECT_EQ(plain.find("uv_vectors"), std::string::npos);
  EXPECT_EQ(plain.find("Rockbake_Use_Maps"), std::string::npos);
  // The studio template asks for the maps; the debug template stays flat.
  const std::string studio = test::readBytes(test::sourceDir() / "render_templates" / "studio.pov");
  const std::string debug = test::readBytes(test::sourceDir() / "render_templates" / "debug.pov");
  EXPECT_NE(studio.find("#declare Rockbake_Use_Maps = 1;"), std::string::npos);
  EXPECT_EQ(debug.find("Rockbake_Use_Maps"), std::string::npos);
}

}  // namespace
}  // namespace rockbake
