// Meshes the texture stage's tests share: analytic surfaces (sphere, torus, plane) and real
// weathered rocks baked in-process through the mesh stage's functions. Header-only, so each
// test file of tests/texture includes it.
#pragma once

#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/surface_mesh.h"
#include "inputs/resolve_shape.h"
#include "mesh/subdivide.h"
#include "pipeline/bake_meshes.h"
#include "preset/load_preset.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake::test {

// A SurfaceMesh from positions and triangles, with area-weighted normals and flat attributes.
inline SurfaceMesh surfaceOf(std::vector<std::array<float, 3>> positions,
                             std::vector<std::array<std::uint32_t, 3>> triangles, const char* name = "rock") {
  SurfaceMesh m;
  m.name = name;
  m.positions = std::move(positions);
  m.triangles = std::move(triangles);
  computeVertexNormals(m);
  const std::size_t n = m.positions.size();
  m.durability.assign(n, 1.0f);
  m.colluvium.assign(n, 0.0f);
  m.curvature.assign(n, 0.5f);
  m.altitude.assign(n, 0.5f);
  m.colors.assign(n, {0.5f, 0.4f, 0.3f});
  return m;
}

// The unit icosphere of `levels` subdivisions, scaled to `radius`.
inline SurfaceMesh sphereSurface(int levels, double radius = 1.0) {
  const TriangleMesh ico = icosphere(levels);
  std::vector<std::array<float, 3>> p;
  for (const auto& q : ico.positions) p.push_back({float(q[0] * radius), float(q[1] * radius), float(q[2] * radius)});
  return surfaceOf(std::move(p), ico.triangles);
}

// A closed torus about the z axis (genus 1: an arch's through-hole), nu × nv quads split in two.
inline SurfaceMesh torusSurface(double major, double minor, int nu, int nv) {
  std::vector<std::array<float, 3>> p;
  std::vector<std::array<std::uint32_t, 3>> t;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double a = 2 * pi * i / nu, b = 2 * pi * j / nv;
      p.push_back({float((major + minor * std::cos(b)) * std::cos(a)),
                   float((major + minor * std::cos(b)) * std::sin(a)), float(minor * std::sin(b))});
    }
  const auto at = [&](int i, int j) { return std::uint32_t(((i + nu) % nu) * nv + (j + nv) % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      t.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      t.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return surfaceOf(std::move(p), std::move(t));
}

inline AssetMeshes assetOf(SurfaceMesh rock, SurfaceMesh colluvium = {}) {
  AssetMeshes a;
  a.rock = std::move(rock);
  a.colluvium = std::move(colluvium);
  a.colluvium.name = "colluvium";
  return a;
}

// A shipped preset baked in-process at a low resolution: its LOD0 (MeshStageResult::meshes).
inline MeshStageResult bakePresetMeshes(const char* preset, int resolution) {
  const Preset p = loadPreset(sourceDir() / "presets" / preset, {{}, {}, resolution});
  const VoxelRock rock = weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
  return buildMeshes(rock, p);
}

// goblin at resolution 32: a weathered rock with layers, colluvium and detail.
inline const MeshStageResult& weatheredRock() {
  static const MeshStageResult r = bakePresetMeshes("goblin.yaml", 32);
  return r;
}

// arch at resolution 64: an arch over the ground in an apron of debris holed through.
inline const MeshStageResult& archRock() {
  static const MeshStageResult r = bakePresetMeshes("arch.yaml", 64);
  return r;
}

// Euler characteristic V − E + F of a closed triangle mesh (2 per sphere, 0 per torus).
inline long eulerCharacteristic(const SurfaceMesh& m) {
  // Each edge of a closed mesh is used twice.
  return long(m.positions.size()) - long(3 * m.triangles.size() / 2) + long(m.triangles.size());
}

}  // namespace rockbake::test
