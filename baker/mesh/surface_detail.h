// Surface detail (docs/meshes.md, `mesh.detail`): seeded roughness below the voxel
// scale, displaced along the refined surface's normals before simplification.
//
// Each rock vertex moves by
//   amplitude · weight(v) · n(p / period) / rms(n)
// where n is `octaves` of improved Perlin noise seeded from (seed, "mesh-detail"),
// rms(n) its root mean square over the mesh's vertices (so a neutral weight of 1
// gives a displacement whose RMS is `amplitude`), and
//   weight(v) = (½ + softness) · (½ + s) · (1 − colluvium coverage)
// with softness = (D_max − D) / (D_max − D_min) over the preset's durability
// range (½ when the range is empty) and s the calibrated exposure (½ flat): soft,
// exposed rock is roughest. Vertices on the ground cap (z = 0 with ground) do
// not move, and no vertex is pushed below z = 0. Where the displacement would
// fold the surface (a triangle turned over or against a neighbour, or
// collapsed), it is halved at that triangle's corners, repeatedly, and dropped
// there if that is not enough: a clean input stays free of fold-overs. The
// result is a pure function of the mesh and the parameters (byte-identical at
// any thread count).
//
// With a weathering process on (DetailProcesses below), the noise keeps
// kNoiseUnderProcesses of its amplitude and each process adds its own
// displacement, c = 1 − colluvium coverage; the ground cap rule and the
// fold-over guard apply to the sum. Without one, the result is the noise
// alone, to the byte.
//   laminations  A · (½ + softness) · c · ridge(b / spacing), b the bed position
//                (z for flat beds). Lamina k lies between partings k and k + 1,
//                each shifted by a seeded ±0.2 spacing, and has a seeded
//                hardness h_k (counterHash(seed, "laminae", 0, k)): its face
//                stands at 0.7 (2 h_k − 1), rounding off within a quarter
//                spacing of a parting into a groove at −0.3. A function of b
//                alone, so the ridges run along the beds' strike.
//   exfoliation  A · w⁺(s) · c · saw(d / spacing + jitter), d = (1 − age) ·
//                retreat (age SurfaceMesh::history[0]): the surface stands at
//                the last sheet boundary the retreat reached, proud by the
//                fraction of the sheet cut through and falling off across the
//                sheet's last 12 %; the boundaries wander by ±0.12 sheet
//                (seeded Perlin noise). w⁺ rises from s = ½ to 0.8. Skipped
//                without a history or a retreat.
//   pitting      −A · w⁻(s) · c · depth · (1 − (r / ½ spacing)²)², r the distance
//                to the nearest pit centre (Worley F1: one seeded centre per
//                cell of `spacing`), depth a seeded ½..1 per pit. w⁻ rises from
//                s = ½ down to 0.2.
#pragma once

#include <cstdint>
#include <functional>

#include "core/surface_mesh.h"
#include "core/vec3.h"
#include "preset/preset.h"

namespace rockbake {

// Relief made by the weathering processes (docs/model.md §14), each a LookRelief (amplitude 0: off):
//   laminations  ridges and partings along the beds: a ridge per lamina of `spacing`, the harder
//                laminae (a seeded hardness per lamina) standing out, strongest on soft rock
//   exfoliation  sheets parallel to the surface on spheroidally weathered (convex) rock: steps
//                where the surface cuts the boundaries between sheets `spacing` thick, the depth
//                read from the exposure age (SurfaceMesh::history) over the run's retreat
//   pitting      granular pits on cavernously weathered (concave) rock, `spacing` across
// With any of them on, the seeded noise is kept as a last, small octave (kNoiseUnderProcesses of
// its amplitude).
struct DetailProcesses {
  LookRelief laminations, exfoliation, pitting;
  // The position along the beds' normal at a world point, world units, increasing upwards through
  // the beds (the simulation's bed altitude times the domain's height); empty: flat beds, z.
  std::function<double(const Vec3d&)> bed_position;
  double retreat = 0.0;  // world units the run could retreat the surface (its time: cycles × h)
  bool any() const { return laminations.amplitude > 0 || exfoliation.amplitude > 0 || pitting.amplitude > 0; }
};
inline constexpr double kNoiseUnderProcesses = 0.35;

struct DetailParams {
  NoiseParams noise;  // amplitude and period in world units, octaves 1..8; amplitude 0: no noise
  std::uint64_t seed = 0;
  float durability_min = 0.0f, durability_max = 1.0f;  // the preset's range over the rock voxels
  bool ground = true;                                  // z = 0 is the ground cap
  DetailProcesses processes;                           // none on: the noise alone, as before
};

// Displaces `mesh` (triangles only, with normals and attributes; history when a process reads
// it) in place and recomputes its normals. An empty mesh, or no noise and no process, leaves it
// unchanged.
void displaceSurface(SurfaceMesh& mesh, const DetailParams& params);

}  // namespace rockbake
