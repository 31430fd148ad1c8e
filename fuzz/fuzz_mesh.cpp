// The blockout readers: the first byte picks the format (OBJ, PLY, STL), the
// rest is the file. Refusals are std::runtime_error; a mesh that reads has
// only finite coordinates and in-range indices.
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "geometry/mesh_checks.h"
#include "fuzz_support.h"
#include "inputs/mesh_reader.h"

using namespace rockbake;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = fuzz::scratchDir("mesh");
  if (size == 0) return 0;
  static const char* const kNames[] = {"blockout.obj", "blockout.ply", "blockout.stl"};
  const std::filesystem::path file = dir / kNames[data[0] % 3];
  fuzz::writeFile(file, {reinterpret_cast<const char*>(data) + 1, size - 1});
  TriangleMesh mesh;
  if (!fuzz::refusesOnlyWith<std::runtime_error>([&] { mesh = readTriangleMesh(file); })) return 0;
  for (const auto& p : mesh.positions)
    for (double c : p)
      if (!std::isfinite(c)) fuzz::finding("a mesh with a non-finite coordinate was accepted");
  for (const auto& t : mesh.triangles)
    for (auto v : t)
      if (v >= mesh.positions.size()) fuzz::finding("a triangle index is past the vertices");
  findOpenEdges(mesh);
  signedVolume(mesh);
  return 0;
}
