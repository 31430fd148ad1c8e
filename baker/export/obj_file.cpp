#include "export/obj_file.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "platform/atomic_file.h"
#include "platform/colour.h"

namespace rockbake {

namespace {

// The material lines of one surface: white diffuse so vertex colours show, and the maps.
std::string materialLines(const std::string& name, const MaterialMaps& maps) {
  std::string m = fmt::format("newmtl {}\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nillum 1\n", name);
  if (!maps.base_color.empty()) m += fmt::format("map_Kd {}\n", maps.base_color);
  if (!maps.normal.empty()) m += fmt::format("norm {}\nmap_Bump -bm 1 {}\n", maps.normal, maps.normal);
  if (!maps.height.empty()) m += fmt::format("disp {}\n", maps.height);
  if (!maps.empty()) m += "Pm 0\n";
  return m;
}

}  // namespace

void writeObj(const AssetMeshes& meshes, const std::filesystem::path& obj, const AssetMeshes* uvs,
              const MaterialMaps& maps) {
  std::filesystem::path mtl = obj;
  mtl.replace_extension(".mtl");
  std::string text = fmt::format(
      "# rockbake: world units, y up (world x, z, -y), pivot at the footprint centre on the ground; vertex colours "
      "sRGB\nmtllib {}\n",
      mtl.filename().string());
  std::string materials = uvs ? "# rockbake materials: white diffuse and the texture set's maps\n"
                              : "# rockbake materials: white diffuse, the vertex colours carry the palette\n";
  auto out = std::back_inserter(text);
  std::size_t base = 1, uv_base = 1;  // OBJ indices are 1-based and global
  for (int s = 0; s < 2; ++s) {
    const SurfaceMesh* m = s == 0 ? &meshes.rock : &meshes.colluvium;
    if (m->positions.empty()) continue;
    const std::size_t n = m->positions.size();
    if (m->normals.size() != n || m->colors.size() != n || !m->quads.empty())
      throw std::runtime_error(
          fmt::format("{}: the {} mesh lacks normals or colours, or has quads", obj.string(), m->name));
    const SurfaceMesh* split = uvs ? (s == 0 ? &uvs->rock : &uvs->colluvium) : nullptr;
    if (split && (split->triangles.size() != m->triangles.size() || split->uvs.size() != split->positions.size()))
      throw std::runtime_error(fmt::format("{}: the {} mesh's uvs do not match its triangles", obj.string(), m->name));
    fmt::format_to(out, "o {}\nusemtl {}\n", m->name, m->name);
    // Text formatting dominates: format blocks of lines in parallel, in order.
    constexpr std::size_t kBlock = 16384;
    const auto formatBlocks = [&](std::size_t count, auto&& line) {
      std::vector<std::string> blocks((count + kBlock - 1) / kBlock);
      tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t b) {
        auto it = std::back_inserter(blocks[b]);
        for (std::size_t i = b * kBlock; i < std::min(count, (b + 1) * kBlock); ++i) line(it, i);
      });
      for (const auto& block : blocks) text += block;
    };
    formatBlocks(n, [&](auto& it, std::size_t i) {
      const auto& p = m->positions[i];
      const auto& c = m->colors[i];
      // y up, as DCCs read OBJ (the same axes as the GLB): world (x, y, z) -> (x, z, -y).
      fmt::format_to(it, "v {} {} {} {:.4f} {:.4f} {:.4f}\n", p[0], p[2], -p[1], linearToSrgb(c[0]), linearToSrgb(c[1]),
                     linearToSrgb(c[2]));
    });
    if (split)
      formatBlocks(split->uvs.size(), [&](auto& it, std::size_t i) {
        fmt::format_to(it, "vt {} {}\n", split->uvs[i][0], 1.0f - split->uvs[i][1]);  // OBJ's v runs up
      });
    formatBlocks(n, [&](auto& it, std::size_t i) {
      const auto& v = m->normals[i];
      fmt::format_to(it, "vn {:.5f} {:.5f} {:.5f}\n", v[0], v[2], -v[1]);
    });
    if (split) {
      formatBlocks(m->triangles.size(), [&](auto& it, std::size_t i) {
        const auto& t = m->triangles[i];
        const auto& u = split->triangles[i];
        const std::size_t a = t[0] + base, b = t[1] + base, c = t[2] + base;
        fmt::format_to(it, "f {}/{}/{} {}/{}/{} {}/{}/{}\n", a, u[0] + uv_base, a, b, u[1] + uv_base, b, c,
                       u[2] + uv_base, c);
      });
      uv_base += split->uvs.size();
    } else {
      formatBlocks(m->triangles.size(), [&](auto& it, std::size_t i) {
        const auto& t = m->triangles[i];
        const std::size_t a = t[0] + base, b = t[1] + base, c = t[2] + base;
        fmt::format_to(it, "f {}//{} {}//{} {}//{}\n", a, a, b, b, c, c);
      });
    }
    base += n;
    materials += materialLines(m->name, split ? maps : MaterialMaps{});
  }
  writeFileAtomically(mtl, materials);
  writeFileAtomically(obj, text);
}

}  // namespace rockbake
