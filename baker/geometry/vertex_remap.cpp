#include "geometry/vertex_remap.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace rockbake {
namespace {

void requireIndices(const SurfaceMesh& mesh, std::span<const std::uint32_t> indices, const char* what) {
  const std::size_t n = mesh.positions.size();
  for (std::uint32_t v : indices)
    if (v >= n)
      throw std::out_of_range("SurfaceMesh \"" + mesh.name + "\": " + what + " names vertex " + std::to_string(v) +
                              " of " + std::to_string(n));
}

}  // namespace

void requireVertexArrays(const SurfaceMesh& mesh) {
  const std::size_t n = mesh.positions.size();
  forEachVertexArray(mesh, [&](const char* name, const auto& values) {
    if (!values.empty() && values.size() != n)
      throw std::logic_error("SurfaceMesh \"" + mesh.name + "\": " + name + " holds " + std::to_string(values.size()) +
                             " values for " + std::to_string(n) +
                             " vertices (a per-vertex array is empty or holds one value per vertex)");
  });
}

SurfaceMesh gatherVertices(const SurfaceMesh& mesh, std::span<const std::uint32_t> source) {
  requireVertexArrays(mesh);
  requireIndices(mesh, source, "a vertex remap");
  SurfaceMesh out;
  out.name = mesh.name;
  std::apply(
      [&](const auto&... array) {
        const auto gather = [&](const auto& from, auto& to) {
          if (from.empty()) return;
          to.resize(source.size());
          for (std::size_t i = 0; i < source.size(); ++i) to[i] = from[source[i]];
        };
        (gather(mesh.*(array.member), out.*(array.member)), ...);
      },
      kVertexArrays);
  return out;
}

void remapVertices(SurfaceMesh& mesh, std::span<const std::uint32_t> new_index) {
  const std::size_t n = mesh.positions.size();
  if (new_index.size() != n)
    throw std::logic_error("SurfaceMesh \"" + mesh.name + "\": a vertex remap of " + std::to_string(new_index.size()) +
                           " entries for " + std::to_string(n) + " vertices");
  std::uint32_t count = 0;
  for (std::uint32_t v : new_index)
    if (v != kDroppedVertex) count = std::max(count, v + 1);
  if (count > n)  // more new vertices than old ones: some new index has no vertex
    throw std::logic_error("SurfaceMesh \"" + mesh.name + "\": a vertex remap leaves a gap in the new indices");
  constexpr std::uint32_t kUnset = kDroppedVertex;
  std::vector<std::uint32_t> source(count, kUnset);
  for (std::uint32_t v = 0; v < n; ++v)
    if (new_index[v] != kDroppedVertex && source[new_index[v]] == kUnset) source[new_index[v]] = v;
  if (std::find(source.begin(), source.end(), kUnset) != source.end())
    throw std::logic_error("SurfaceMesh \"" + mesh.name + "\": a vertex remap leaves a gap in the new indices");
  const auto requireKept = [&](const auto& faces) {
    for (const auto& f : faces)
      for (std::uint32_t v : f)
        if (v >= n || new_index[v] == kDroppedVertex)
          throw std::logic_error("SurfaceMesh \"" + mesh.name + "\": a face uses vertex " + std::to_string(v) +
                                 ", which a vertex remap drops");
  };
  requireKept(mesh.triangles);
  requireKept(mesh.quads);
  SurfaceMesh out = gatherVertices(mesh, source);
  const auto renumber = [&](auto& faces) {
    for (auto& f : faces)
      for (auto& v : f) v = new_index[v];
  };
  renumber(mesh.triangles);
  renumber(mesh.quads);
  out.triangles = std::move(mesh.triangles);
  out.quads = std::move(mesh.quads);
  mesh = std::move(out);
}

std::size_t compactVertices(SurfaceMesh& mesh) {
  const std::size_t n = mesh.positions.size();
  std::vector<std::uint32_t> new_index(n, kDroppedVertex);
  const auto mark = [&](const auto& faces) {
    for (const auto& f : faces)
      for (std::uint32_t v : f) {
        if (v >= n)
          throw std::out_of_range("SurfaceMesh \"" + mesh.name + "\": a face names vertex " + std::to_string(v) +
                                  " of " + std::to_string(n));
        new_index[v] = 0;
      }
  };
  mark(mesh.triangles);
  mark(mesh.quads);
  std::uint32_t next = 0;
  for (auto& i : new_index)
    if (i != kDroppedVertex) i = next++;
  remapVertices(mesh, new_index);
  return n - next;
}

void compactMesh(SurfaceMesh& mesh) {
  std::erase_if(mesh.triangles, [](const auto& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; });
  compactVertices(mesh);
}

void appendVertexCopies(SurfaceMesh& mesh, std::span<const std::uint32_t> originals) {
  std::vector<std::uint32_t> source(mesh.positions.size());
  std::iota(source.begin(), source.end(), 0u);
  source.insert(source.end(), originals.begin(), originals.end());
  SurfaceMesh out = gatherVertices(mesh, source);
  out.triangles = std::move(mesh.triangles);
  out.quads = std::move(mesh.quads);
  mesh = std::move(out);
}

}  // namespace rockbake
