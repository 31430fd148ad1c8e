#include "texture/tangents.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/vec3.h"

namespace rockbake {

constexpr Vec3d kZero{0.0, 0.0, 0.0};  // normalised()'s fallback: a zero vector stays zero

void computeTangents(SurfaceMesh& mesh) {
  const std::size_t n = mesh.positions.size();
  if (n == 0) {
    mesh.tangents.clear();
    return;
  }
  if (mesh.normals.size() != n || mesh.uvs.size() != n)
    throw std::invalid_argument("computeTangents: the " + mesh.name + " mesh lacks normals or uvs");
  // Per vertex, the angle-weighted sums of the projected tangents of its triangles that keep
  // the surface's orientation ([0]) and of those that mirror it ([1]), and their angles.
  std::vector<std::array<Vec3d, 2>> sum(n, {Vec3d{0, 0, 0}, Vec3d{0, 0, 0}});
  std::vector<std::array<double, 2>> weight(n, {0.0, 0.0});
  for (const auto& tri : mesh.triangles) {
    const Vec3d p0 = toVec3d(mesh.positions[tri[0]]), p1 = toVec3d(mesh.positions[tri[1]]),
                p2 = toVec3d(mesh.positions[tri[2]]);
    const auto st = [&](int k) {
      return std::array<double, 2>{mesh.uvs[tri[k]][0], 1.0 - double(mesh.uvs[tri[k]][1])};
    };
    const auto t0 = st(0), t1 = st(1), t2 = st(2);
    const double s21 = t1[0] - t0[0], t21 = t1[1] - t0[1], s31 = t2[0] - t0[0], t31 = t2[1] - t0[1];
    const double signed_area = s21 * t31 - t21 * s31;
    const Vec3d d1 = sub(p1, p0), d2 = sub(p2, p0);
    // ∂p/∂s up to the factor 1 / signed_area, whose sign the orientation carries.
    Vec3d tangent = sub(scale(d1, t31), scale(d2, t21));
    if (signed_area < 0) tangent = scale(tangent, -1.0);
    if (signed_area == 0 || length(cross(d1, d2)) == 0 || length(tangent) == 0) continue;
    const int side = signed_area > 0 ? 0 : 1;
    const Vec3d corner[3] = {p0, p1, p2};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = tri[k];
      const Vec3d normal = normalised(toVec3d(mesh.normals[v]), kZero);
      const auto project = [&](const Vec3d& a) { return normalised(sub(a, scale(normal, dot(normal, a))), kZero); };
      const Vec3d along = project(tangent);
      const Vec3d e1 = project(sub(corner[(k + 1) % 3], corner[k])), e2 = project(sub(corner[(k + 2) % 3], corner[k]));
      const double angle = std::acos(std::clamp(dot(e1, e2), -1.0, 1.0));
      sum[v][side] = add(sum[v][side], scale(along, angle));
      weight[v][side] += angle;
    }
  }
  mesh.tangents.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    const int side = weight[v][1] > weight[v][0] ? 1 : 0;
    const Vec3d normal = normalised(toVec3d(mesh.normals[v]), kZero);
    Vec3d t = normalised(sub(sum[v][side], scale(normal, dot(normal, sum[v][side]))), kZero);
    if (length(t) == 0) {
      // Nothing to go by: the axis least aligned with the normal, made perpendicular to it.
      const int axis = std::abs(normal[0]) <= std::abs(normal[1]) && std::abs(normal[0]) <= std::abs(normal[2]) ? 0
                       : std::abs(normal[1]) <= std::abs(normal[2])                                             ? 1
                                                                                                                : 2;
      Vec3d e{0, 0, 0};
      e[std::size_t(axis)] = 1;
      t = normalised(sub(e, scale(normal, dot(normal, e))), kZero);
    }
    mesh.tangents[v] = {float(t[0]), float(t[1]), float(t[2]), side == 0 ? 1.0f : -1.0f};
  }
}

}  // namespace rockbake
