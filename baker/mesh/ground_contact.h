// Where an asset meets the ground (docs/meshes.md, "The ground contact"): the line along which its
// visible surface comes down onto the ground plane, and each point's horizontal distance from it.
//
// A surface resting on the ground closes with a flat cap on z = ground (mesh/extract_surfaces.h);
// the cap's rim, where it meets the rest of the surface, is where the surface touches the ground.
// Rims of the rock and the colluvium that run together (within `shared` of each other: the
// colluvium lying against the rock's foot) are buried, not seen, and are left out; what is left
// is the apron's outer rim and the rock's bare foot. Distances are kept on a grid of `cell`
// across (an exact Euclidean distance transform, Felzenszwalb and Huttenlocher 2012, from the
// cells the contact points fall in, PlaneDistance), read bilinearly: within about a cell of the
// exact distance.
#pragma once

#include <array>
#include <limits>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

// Points along the rim of `mesh`'s ground cap, (x, y) each: its vertices (at z <= ground + eps,
// on a triangle not all on the cap) and, on its edges between two of them, points at most
// `spacing` apart.
std::vector<std::array<double, 2>> groundCapRim(const SurfaceMesh& mesh, double ground, double eps,
                                                double spacing);

// The contact points of `meshes` on the ground plane z = `ground`: both surfaces' cap rims,
// less the stretches where rock and colluvium rims run within `shared` of each other.
std::vector<std::array<double, 2>> groundContactPoints(const AssetMeshes& meshes, double ground, double eps,
                                                       double shared, double spacing);

// Distances in the plane from a set of points, on a grid of `cell` over [lo, hi] (a cell's margin
// added): exact from the cells the points fall in, read bilinearly.
class PlaneDistance {
 public:
  PlaneDistance(const std::vector<std::array<double, 2>>& points, std::array<double, 2> lo, std::array<double, 2> hi,
                double cell);

  bool empty() const { return distance_.empty(); }
  // The distance from (x, y) to the nearest point: infinity with none; beyond the grid, the
  // distance at its nearest cell plus the way out to it.
  double at(double x, double y) const;
  // Its gradient by central differences over a cell (a unit vector where the field is a distance).
  std::array<double, 2> gradient(double x, double y) const;

 private:
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<double> distance_;  // per cell (x fastest), world units
};

}  // namespace rockbake
