// Small analytic meshes for the mesh kernel's tests, whose counts can be
// checked by hand: a tetrahedron, unit cubes (as triangles or quads, alone,
// two sharing an edge or a vertex), a cube with a face missing.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake::test {

// Builds a mesh from faces given by corner positions, welding equal positions.
class MeshBuilder {
 public:
  explicit MeshBuilder(std::string name = "rock") { mesh_.name = std::move(name); }

  std::uint32_t vertex(const std::array<float, 3>& p) {
    const auto [it, fresh] = index_.try_emplace(p, std::uint32_t(mesh_.positions.size()));
    if (fresh) mesh_.positions.push_back(p);
    return it->second;
  }
  void triangle(const std::array<float, 3>& a, const std::array<float, 3>& b, const std::array<float, 3>& c) {
    mesh_.triangles.push_back({vertex(a), vertex(b), vertex(c)});
  }
  // A quad's corners counter-clockwise from outside: two triangles (0, 1, 2),
  // (0, 2, 3), or one quad face.
  void quad(const std::array<std::array<float, 3>, 4>& q, bool as_quad = false) {
    if (as_quad) {
      mesh_.quads.push_back({vertex(q[0]), vertex(q[1]), vertex(q[2]), vertex(q[3])});
      return;
    }
    triangle(q[0], q[1], q[2]);
    triangle(q[0], q[2], q[3]);
  }
  // The unit cube at `o`, faces outward; `skip_top` leaves its +z face out (a hole).
  void cube(const std::array<float, 3>& o, bool as_quads = false, bool skip_top = false) {
    const auto p = [&](float x, float y, float z) { return std::array<float, 3>{o[0] + x, o[1] + y, o[2] + z}; };
    quad({p(0, 0, 0), p(0, 0, 1), p(0, 1, 1), p(0, 1, 0)}, as_quads);                 // -x
    quad({p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)}, as_quads);                 // +x
    quad({p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)}, as_quads);                 // -y
    quad({p(0, 1, 0), p(0, 1, 1), p(1, 1, 1), p(1, 1, 0)}, as_quads);                 // +y
    quad({p(0, 0, 0), p(0, 1, 0), p(1, 1, 0), p(1, 0, 0)}, as_quads);                 // -z
    if (!skip_top) quad({p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)}, as_quads);  // +z
  }
  SurfaceMesh& mesh() { return mesh_; }

 private:
  SurfaceMesh mesh_;
  std::map<std::array<float, 3>, std::uint32_t> index_;
};

// Four outward triangles on the corners of the unit simplex.
inline SurfaceMesh tetrahedron() {
  MeshBuilder b;
  const std::array<float, 3> o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  b.triangle(o, y, x), b.triangle(o, x, z), b.triangle(o, z, y), b.triangle(x, y, z);
  return b.mesh();
}

inline SurfaceMesh unitCube(bool as_quads = false) {
  MeshBuilder b;
  b.cube({0, 0, 0}, as_quads);
  return b.mesh();
}

// Two unit cubes sharing the edge x = y = 1, 0 <= z <= 1 (four faces on it).
inline SurfaceMesh cubesSharingAnEdge() {
  MeshBuilder b;
  b.cube({0, 0, 0}), b.cube({1, 1, 0});
  return b.mesh();
}

// Two unit cubes sharing the vertex (1, 1, 1): every edge paired, one vertex pinched.
inline SurfaceMesh cubesSharingAVertex() {
  MeshBuilder b;
  b.cube({0, 0, 0}), b.cube({1, 1, 1});
  return b.mesh();
}

// The unit cube without its top: a square hole of four edges.
inline SurfaceMesh openBox() {
  MeshBuilder b;
  b.cube({0, 0, 0}, false, true);
  return b.mesh();
}

}  // namespace rockbake::test
