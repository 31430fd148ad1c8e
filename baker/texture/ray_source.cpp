#include "texture/ray_source.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rockbake {

struct RaySource::Scene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  unsigned geometry[2] = {RTC_INVALID_GEOMETRY_ID, RTC_INVALID_GEOMETRY_ID};
  double radius = 0;
  // Rays start this far back, so a point on the surface is found: well above a float
  // position's rounding even where the ray runs nearly along the triangle (1/50 of its slope).
  float epsilon = 0;
  const SurfaceMesh* surfaces[2] = {nullptr, nullptr};  // the source's, read by the facing rule

  ~Scene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

constexpr int kLanes = RaySource::kPacket;

// The intersect calls' context, carrying each lane's query: which surface, and the nearest
// hit accepted so far with its triangle (for the tie rule); the surface's mesh and the way
// the rays run (+1 along the asked direction, −1 against it), for the facing rule.
struct QueryContext {
  RTCIntersectContext base;
  unsigned surface_geometry[kLanes];
  const SurfaceMesh* surface_mesh[kLanes];
  float way = 1.0f;
  float best_t[kLanes];
  unsigned best_triangle[kLanes];
};

// The facing rule: the source's own normal at the candidate (its vertex normals interpolated,
// what every map reads there) faces the asked direction's side. A surface seen from its back
// (the far wall of a groove the LOD spans, a fold) would bake a normal pointing into the rock
// and colours from the wrong side; the nearest surface facing the same way is the one the LOD
// stands for, and a texel with none keeps the LOD's own values (a miss).
bool facesTheAskedWay(const QueryContext& query, const RTCFilterFunctionNArguments* args, unsigned i,
                      unsigned triangle) {
  const SurfaceMesh& m = *query.surface_mesh[i];
  const auto& tri = m.triangles[triangle];
  const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
  const float w[3] = {1.0f - u - v, u, v};
  const float d[3] = {RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                      RTCRayN_dir_z(args->ray, args->N, i)};
  float along = 0.0f;
  for (int c = 0; c < 3; ++c) {
    const auto& n = m.normals[tri[std::size_t(c)]];
    along += w[c] * (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
  }
  return query.way * along > 0.0f;
}

// Accepts a candidate only on the asked-for surface, facing the asked way, and at a distance
// equal to the best so far only with a lower triangle index. Embree sets a lane's tfar to the
// candidate's distance before the call (and restores it on a rejection); a single ray is lane
// 0, a packet's ray is its lane, one at a time or several at once.
void tieBreak(const RTCFilterFunctionNArguments* args) {
  auto* query = reinterpret_cast<QueryContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned geometry = RTCHitN_geomID(args->hit, args->N, i);
    const unsigned triangle = RTCHitN_primID(args->hit, args->N, i);
    const float t = RTCRayN_tfar(args->ray, args->N, i);
    if (geometry != query->surface_geometry[i] ||
        !(t < query->best_t[i] || (t == query->best_t[i] && triangle < query->best_triangle[i])) ||
        !facesTheAskedWay(*query, args, i, triangle)) {
      args->valid[i] = 0;
      continue;
    }
    query->best_t[i] = t;
    query->best_triangle[i] = triangle;
  }
}

[[noreturn]] void fail(RTCDevice device, const char* what) {
  const RTCError e = device ? rtcGetDeviceError(device) : RTC_ERROR_UNKNOWN;
  throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(int(e)) + ")");
}

unsigned addSurface(RTCDevice device, RTCScene scene, const SurfaceMesh& mesh) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (!g) fail(device, "rtcNewGeometry");
  // Vertices in a buffer of Embree's own (it may read 16 bytes from a 12-byte vertex and pads
  // its buffers for that); the triangles read in place.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
  if (!vertices) {
    rtcReleaseGeometry(g);
    fail(device, "rtcSetNewGeometryBuffer");
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = mesh.positions[i][k];
  static_assert(sizeof(mesh.triangles[0]) == 3 * sizeof(unsigned));
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.triangles.data(), 0,
                             3 * sizeof(unsigned), mesh.triangles.size());
  rtcSetGeometryIntersectFilterFunction(g, tieBreak);
  rtcCommitGeometry(g);
  const unsigned id = rtcAttachGeometry(scene, g);
  rtcReleaseGeometry(g);
  return id;
}

}  // namespace

RaySource::RaySource(const AssetMeshes& source) : scene_(std::make_unique<Scene>()) {
  Scene& s = *scene_;
  s.device = rtcNewDevice(nullptr);
  if (!s.device) fail(nullptr, "rtcNewDevice");
  s.scene = rtcNewScene(s.device);
  if (!s.scene) fail(s.device, "rtcNewScene");
  rtcSetSceneFlags(
      s.scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT);  // compact: a hero's source is millions of triangles
  rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_MEDIUM);    // HIGH's spatial splits are not deterministic
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  const SurfaceMesh* surfaces[2] = {&source.rock, &source.colluvium};
  for (int i = 0; i < 2; ++i) {
    const SurfaceMesh& m = *surfaces[i];
    for (const auto& p : m.positions)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(p[k])), hi[k] = std::max(hi[k], double(p[k]));
    s.surfaces[i] = &m;
    if (!m.triangles.empty()) s.geometry[i] = addSurface(s.device, s.scene, m);
  }
  rtcCommitScene(s.scene);
  if (rtcGetDeviceError(s.device) != RTC_ERROR_NONE) fail(s.device, "rtcCommitScene");
  if (lo[0] <= hi[0])
    s.radius = 0.5 * std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                               (hi[2] - lo[2]) * (hi[2] - lo[2]));
  s.epsilon = float(std::max(1e-4 * s.radius, 1e-9));
}

RaySource::~RaySource() = default;

double RaySource::radius() const {
  return scene_->radius;
}

SourceHit RaySource::nearestAlong(int surface, const std::array<float, 3>& origin,
                                  const std::array<float, 3>& direction, float reach) const {
  const Scene& s = *scene_;
  SourceHit best;
  if (surface < 0 || surface > 1 || s.geometry[surface] == RTC_INVALID_GEOMETRY_ID) return best;
  const float eps = s.epsilon;
  // Ahead first; behind only closer than what ahead found (ahead wins a tie).
  float limit = reach;
  for (int way = 0; way < 2; ++way) {
    const float sign = way == 0 ? 1.0f : -1.0f;
    QueryContext query;
    rtcInitIntersectContext(&query.base);
    query.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    query.surface_geometry[0] = s.geometry[surface];
    query.surface_mesh[0] = s.surfaces[surface];
    query.way = sign;
    query.best_t[0] = std::numeric_limits<float>::infinity();
    query.best_triangle[0] = RTC_INVALID_GEOMETRY_ID;
    RTCRayHit rh;
    rh.ray.org_x = origin[0] - sign * eps * direction[0];
    rh.ray.org_y = origin[1] - sign * eps * direction[1];
    rh.ray.org_z = origin[2] - sign * eps * direction[2];
    rh.ray.dir_x = sign * direction[0];
    rh.ray.dir_y = sign * direction[1];
    rh.ray.dir_z = sign * direction[2];
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = way == 0 ? limit + eps : std::nextafter(limit + eps, 0.0f);
    rh.ray.mask = 0xffffffffu;
    rh.ray.time = 0.0f;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s.scene, &query.base, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    const float distance = rh.ray.tfar - eps;
    best = {true, rh.hit.primID, rh.hit.u, rh.hit.v, sign * distance};
    limit = std::max(distance, 0.0f);
  }
  return best;
}

void RaySource::nearestAlong(int count, const int* surface, const std::array<float, 3>* origin,
                             const std::array<float, 3>* direction, float reach, SourceHit* hits) const {
  const Scene& s = *scene_;
  const float eps = s.epsilon;
  alignas(32) int valid[kLanes];
  float limit[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    const bool live =
        i < count && surface[i] >= 0 && surface[i] <= 1 && s.geometry[surface[i]] != RTC_INVALID_GEOMETRY_ID;
    valid[i] = live ? -1 : 0;
    limit[i] = reach;
    if (i < count) hits[i] = SourceHit{};
  }
  // Ahead first; behind only closer than what ahead found (ahead wins a tie).
  for (int way = 0; way < 2; ++way) {
    const float sign = way == 0 ? 1.0f : -1.0f;
    QueryContext query;
    rtcInitIntersectContext(&query.base);
    query.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    query.way = sign;
    alignas(32) RTCRayHit8 rh;
    for (int i = 0; i < kLanes; ++i) {
      query.surface_geometry[i] = s.geometry[valid[i] ? surface[i] : 0];
      query.surface_mesh[i] = s.surfaces[valid[i] ? surface[i] : 0];
      query.best_t[i] = std::numeric_limits<float>::infinity();
      query.best_triangle[i] = RTC_INVALID_GEOMETRY_ID;
      const std::array<float, 3> o = i < count ? origin[i] : std::array<float, 3>{0, 0, 0};
      const std::array<float, 3> d = i < count ? direction[i] : std::array<float, 3>{0, 0, 1};
      rh.ray.org_x[i] = o[0] - sign * eps * d[0];
      rh.ray.org_y[i] = o[1] - sign * eps * d[1];
      rh.ray.org_z[i] = o[2] - sign * eps * d[2];
      rh.ray.dir_x[i] = sign * d[0];
      rh.ray.dir_y[i] = sign * d[1];
      rh.ray.dir_z[i] = sign * d[2];
      rh.ray.tnear[i] = 0.0f;
      rh.ray.tfar[i] = way == 0 ? limit[i] + eps : std::nextafter(limit[i] + eps, 0.0f);
      rh.ray.mask[i] = 0xffffffffu;
      rh.ray.time[i] = 0.0f;
      rh.ray.flags[i] = 0;
      rh.ray.id[i] = unsigned(i);
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, s.scene, &query.base, &rh);
    for (int i = 0; i < count; ++i) {
      if (!valid[i] || rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
      const float distance = rh.ray.tfar[i] - eps;
      hits[i] = {true, rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i], sign * distance};
      limit[i] = std::max(distance, 0.0f);
    }
  }
}

int RaySource::occludedCount(const std::array<float, 3>& origin, int count, const std::array<float, 3>* directions,
                             float start, float reach) const {
  const Scene& s = *scene_;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(32) int valid[kLanes];
  alignas(32) RTCRay8 ray;
  for (int i = 0; i < kLanes; ++i) {
    valid[i] = i < count ? -1 : 0;
    const std::array<float, 3> d = i < count ? directions[i] : std::array<float, 3>{0, 0, 1};
    ray.org_x[i] = origin[0], ray.org_y[i] = origin[1], ray.org_z[i] = origin[2];
    ray.dir_x[i] = d[0], ray.dir_y[i] = d[1], ray.dir_z[i] = d[2];
    ray.tnear[i] = start;
    ray.tfar[i] = reach;
    ray.mask[i] = 0xffffffffu;
    ray.time[i] = 0.0f;
    ray.flags[i] = 0;
    ray.id[i] = unsigned(i);
  }
  rtcOccluded8(valid, s.scene, &context, &ray);
  int occluded = 0;
  for (int i = 0; i < count; ++i) occluded += ray.tfar[i] < 0.0f;
  return occluded;
}

}  // namespace rockbake
