#include "mesh/subdivide.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/sdc/crease.h>

#include "core/vec3.h"
#include "geometry/edge_table.h"
#include "geometry/triangle_geometry.h"

namespace rockbake {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// One vertex's refined data: position and the four primvars.
struct Primvars {
  float v[10];  // position, durability, colluvium, curvature, altitude, history
  void Clear(void* = nullptr) {
    for (float& x : v) x = 0.0f;
  }
  void AddWithWeight(const Primvars& src, float weight) {
    for (int i = 0; i < 10; ++i) v[i] += weight * src.v[i];
  }
};

void splitQuads(SurfaceMesh& m) {
  m.triangles.reserve(m.triangles.size() + 2 * m.quads.size());
  for (const auto& q : m.quads) {
    if (distanceSquared(m.positions[q[0]], m.positions[q[2]]) <=
        distanceSquared(m.positions[q[1]], m.positions[q[3]])) {
      m.triangles.push_back({q[0], q[1], q[2]});
      m.triangles.push_back({q[0], q[2], q[3]});
    } else {
      m.triangles.push_back({q[0], q[1], q[3]});
      m.triangles.push_back({q[1], q[2], q[3]});
    }
  }
  m.quads.clear();
}

// The ground cap (faces lying on z = 0) meets the walls along an infinitely
// sharp crease, so the refined surface keeps a flat cap and a crisp foot on
// the ground instead of rounding up off it. The creased edges' vertex pairs,
// each edge once (a < b), between a face each way of which one lies on the
// ground (the last such face each way, where an edge has more).
std::vector<Far::Index> groundCreases(const SurfaceMesh& mesh) {
  const std::size_t triangles = mesh.triangles.size();
  std::vector<char> on_ground(triangles + mesh.quads.size(), 1);
  const auto onGround = [&](const auto& face) {
    for (std::uint32_t v : face)
      if (mesh.positions[v][2] != 0.0f) return false;
    return true;
  };
  for (std::size_t f = 0; f < triangles; ++f) on_ground[f] = onGround(mesh.triangles[f]);
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) on_ground[triangles + q] = onGround(mesh.quads[q]);
  const EdgeTable edges(mesh.triangles, mesh.quads);
  std::vector<Far::Index> pairs;
  for (std::uint32_t e = 0; e < edges.edges().size(); ++e) {
    const EdgeTable::Edge& edge = edges.edge(e);
    if (edge.a == edge.b || edge.forward == 0 || edge.backward == 0) continue;
    if (on_ground[edges.face(edges.forwardCorners(e).back())] != on_ground[edges.face(edges.backwardCorners(e).back())])
      pairs.insert(pairs.end(), {Far::Index(edge.a), Far::Index(edge.b)});
  }
  return pairs;
}

// The mesh's faces, ground creases infinitely sharp (groundCreases), refined
// `levels` times uniformly by Catmull-Clark. Throws std::invalid_argument if
// OpenSubdiv refuses the topology.
std::unique_ptr<Far::TopologyRefiner> refineTopology(const SurfaceMesh& mesh, int levels) {
  const std::size_t nf = mesh.triangles.size() + mesh.quads.size();
  std::vector<int> verts_per_face;
  std::vector<Far::Index> indices;
  verts_per_face.reserve(nf);
  indices.reserve(3 * mesh.triangles.size() + 4 * mesh.quads.size());
  for (const auto& t : mesh.triangles) {
    verts_per_face.push_back(3);
    indices.insert(indices.end(), t.begin(), t.end());
  }
  for (const auto& q : mesh.quads) {
    verts_per_face.push_back(4);
    indices.insert(indices.end(), q.begin(), q.end());
  }
  const std::vector<Far::Index> crease_pairs = groundCreases(mesh);
  const std::vector<float> crease_weights(crease_pairs.size() / 2, Sdc::Crease::SHARPNESS_INFINITE);

  Far::TopologyDescriptor desc;
  desc.numVertices = int(mesh.positions.size());
  desc.numFaces = int(nf);
  desc.numVertsPerFace = verts_per_face.data();
  desc.vertIndicesPerFace = indices.data();
  desc.numCreases = int(crease_weights.size());
  desc.creaseVertexIndexPairs = crease_pairs.data();
  desc.creaseWeights = crease_weights.data();

  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc)));
  if (!refiner) throw std::invalid_argument("OpenSubdiv refused the " + mesh.name + " mesh's topology");
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
  return refiner;
}

// The position, the four baked attributes and the history of every vertex of the
// refiner's last level (an absent attribute refines its default).
std::vector<Primvars> refinePrimvars(const SurfaceMesh& mesh, const Far::TopologyRefiner& refiner) {
  // Primvars of every level, one buffer: level 0 first, each level after the previous.
  std::vector<Primvars> buffer(std::size_t(refiner.GetNumVerticesTotal()));
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    buffer[i] = {{p[0], p[1], p[2], mesh.durability.empty() ? 0.0f : mesh.durability[i],
                  mesh.colluvium.empty() ? 0.0f : mesh.colluvium[i], mesh.curvature.empty() ? 0.5f : mesh.curvature[i],
                  mesh.altitude.empty() ? 0.0f : mesh.altitude[i]}};
    if (!mesh.history.empty())
      for (int k = 0; k < 3; ++k) buffer[i].v[7 + k] = mesh.history[i][std::size_t(k)];
  }
  Far::PrimvarRefiner primvars(refiner);
  Primvars* src = buffer.data();
  for (int level = 1; level <= refiner.GetMaxLevel(); ++level) {
    Primvars* dst = src + refiner.GetLevel(level - 1).GetNumVertices();
    primvars.Interpolate(level, src, dst);
    src = dst;
  }
  return {src, buffer.data() + buffer.size()};
}

// The refiner's last level as a quad mesh with positions and attributes.
SurfaceMesh refinedMesh(const Far::TopologyRefiner& refiner, const std::vector<Primvars>& vertices, bool history) {
  const Far::TopologyLevel& last = refiner.GetLevel(refiner.GetMaxLevel());
  const std::size_t n = std::size_t(last.GetNumVertices());
  SurfaceMesh out;
  out.positions.resize(n);
  out.durability.resize(n);
  out.colluvium.resize(n);
  out.curvature.resize(n);
  out.altitude.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float* v = vertices[i].v;
    out.positions[i] = {v[0], v[1], v[2]};
    out.durability[i] = v[3], out.colluvium[i] = v[4], out.curvature[i] = v[5], out.altitude[i] = v[6];
  }
  if (history) {
    out.history.resize(n);
    for (std::size_t i = 0; i < n; ++i) out.history[i] = {vertices[i].v[7], vertices[i].v[8], vertices[i].v[9]};
  }
  out.quads.reserve(std::size_t(last.GetNumFaces()));
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const auto fv = last.GetFaceVertices(f);
    if (fv.size() != 4) throw std::logic_error("Catmull-Clark refinement produced a non-quad face");
    out.quads.push_back({std::uint32_t(fv[0]), std::uint32_t(fv[1]), std::uint32_t(fv[2]), std::uint32_t(fv[3])});
  }
  return out;
}

}  // namespace

std::size_t catmullClarkVertexCount(std::size_t vertices, std::size_t triangles, std::size_t quads, int levels) {
  std::size_t v = vertices, corners = 3 * triangles + 4 * quads, f = triangles + quads;
  std::size_t e = corners / 2;
  for (int l = 0; l < levels; ++l) {
    const std::size_t v1 = v + e + f, e1 = 2 * e + corners, f1 = corners;
    v = v1, e = e1, f = f1, corners = 4 * f1;
  }
  return v;
}

void computeVertexNormals(SurfaceMesh& m) {
  std::vector<Vec3d> acc(m.positions.size(), {0.0, 0.0, 0.0});
  for (const auto& t : m.triangles) {
    const Vec3d n = triangleNormal(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
    for (auto i : t) acc[i] = add(acc[i], n);  // |n| = 2 × area: area-weighted
  }
  m.normals.resize(m.positions.size());
  for (std::size_t i = 0; i < acc.size(); ++i) m.normals[i] = toVec3f(normalised(acc[i], Vec3d{0.0, 0.0, 1.0}));
}

SurfaceMesh subdivideSurface(const SurfaceMesh& mesh, const SubdivideParams& params) {
  if (params.levels < 0 || params.levels > 3)
    throw std::invalid_argument("mesh.subdivision must be 0..3, got " + std::to_string(params.levels));
  SurfaceMesh out;
  if (params.levels == 0 || mesh.positions.empty()) {
    out.positions = mesh.positions;
    out.triangles = mesh.triangles;
    out.quads = mesh.quads;
    out.durability = mesh.durability;
    out.colluvium = mesh.colluvium;
    out.curvature = mesh.curvature;
    out.altitude = mesh.altitude;
    out.history = mesh.history;
  } else {
    const std::unique_ptr<Far::TopologyRefiner> refiner = refineTopology(mesh, params.levels);
    out = refinedMesh(*refiner, refinePrimvars(mesh, *refiner), !mesh.history.empty());
  }
  out.name = mesh.name;
  splitQuads(out);
  computeVertexNormals(out);
  return out;
}

}  // namespace rockbake
