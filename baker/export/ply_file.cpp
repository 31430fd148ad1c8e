#include "export/ply_file.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "platform/atomic_file.h"
#include "platform/colour.h"

namespace rockbake {
namespace {

template <typename T>
void put(std::string& out, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // the project targets little-endian hosts (x86-64, arm64)
  out.append(bytes, sizeof(T));
}

}  // namespace

void writePly(const SurfaceMesh& m, const std::filesystem::path& file) {
  const std::size_t n = m.positions.size();
  if (m.normals.size() != n || m.colors.size() != n || m.durability.size() != n || m.colluvium.size() != n ||
      m.curvature.size() != n || !m.quads.empty())
    throw std::runtime_error(
        fmt::format("{}: the {} mesh lacks normals, colours or attributes, or has quads", file.string(), m.name));
  std::string out = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment rockbake {} surface; world units, z up; colours sRGB\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "property float durability\nproperty float colluvium\nproperty float curvature\n"
      "element face {}\nproperty list uchar {} vertex_indices\nend_header\n",
      m.name, n, m.triangles.size(), n <= 65536 ? "ushort" : "uint");
  // Indices in 16 bits where they fit, as the GLB's: a fifth off a small surface's file.
  const bool narrow = n <= 65536;
  out.reserve(out.size() + n * 39 + m.triangles.size() * (narrow ? 7 : 13));
  for (std::size_t i = 0; i < n; ++i) {
    for (float x : m.positions[i]) put(out, x);
    for (float x : m.normals[i]) put(out, x);
    for (float x : m.colors[i]) put(out, linearToSrgbByte(x));
    put(out, m.durability[i]);
    put(out, m.colluvium[i]);
    put(out, m.curvature[i]);
  }
  for (const auto& t : m.triangles) {
    put(out, std::uint8_t(3));
    for (std::uint32_t i : t) narrow ? put(out, std::uint16_t(i)) : put(out, i);
  }
  writeFileAtomically(file, out);
}

}  // namespace rockbake
