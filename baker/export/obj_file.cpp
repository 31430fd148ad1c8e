#include "export/obj_file.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/atomic_file.h"
#include "core/colour.h"

namespace rockbake {

void writeObj(const AssetMeshes& meshes, const std::filesystem::path& obj) {
  std::filesystem::path mtl = obj;
  mtl.replace_extension(".mtl");
  std::string text = fmt::format(
      "# rockbake: world units, y up (world x, z, -y), pivot at the footprint centre on the ground; vertex colours "
      "sRGB\nmtllib {}\n",
      mtl.filename().string());
  std::string materials = "# rockbake materials: white diffuse, the vertex colours carry the palette\n";
  auto out = std::back_inserter(text);
  std::size_t base = 1;  // OBJ indices are 1-based and global
  for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium}) {
    if (m->positions.empty()) continue;
    const std::size_t n = m->positions.size();
    if (m->normals.size() != n || m->colors.size() != n || !m->quads.empty())
      throw std::runtime_error(
          fmt::format("{}: the {} mesh lacks normals or colours, or has quads", obj.string(), m->name));
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
    formatBlocks(n, [&](auto& it, std::size_t i) {
      const auto& v = m->normals[i];
      fmt::format_to(it, "vn {:.5f} {:.5f} {:.5f}\n", v[0], v[2], -v[1]);
    });
    formatBlocks(m->triangles.size(), [&](auto& it, std::size_t i) {
      const auto& t = m->triangles[i];
      const std::size_t a = t[0] + base, b = t[1] + base, c = t[2] + base;
      fmt::format_to(it, "f {}//{} {}//{} {}//{}\n", a, a, b, b, c, c);
    });
    base += n;
    materials += fmt::format("newmtl {}\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\nillum 1\n", m->name);
  }
  writeFileAtomically(mtl, materials);
  writeFileAtomically(obj, text);
}

}  // namespace rockbake
