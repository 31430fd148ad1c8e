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

  ~Scene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

// rtcIntersect1's context, carrying the query: which surface, and the nearest hit accepted
// so far with its triangle (for the tie rule).
struct QueryContext {
  RTCIntersectContext base;
  unsigned surface_geometry;
  float best_t;
  unsigned best_triangle;
};

// Accepts a candidate only on the asked-for surface, and at a distance equal to the best so
// far only with a lower triangle index. Embree sets tfar to the candidate's distance before
// the call (and restores it on a rejection).
void tieBreak(const RTCFilterFunctionNArguments* args) {
  auto* query = reinterpret_cast<QueryContext*>(args->context);
  const unsigned geometry = RTCHitN_geomID(args->hit, args->N, 0);
  const unsigned triangle = RTCHitN_primID(args->hit, args->N, 0);
  const float t = RTCRayN_tfar(args->ray, args->N, 0);
  if (geometry != query->surface_geometry ||
      !(t < query->best_t || (t == query->best_t && triangle < query->best_triangle))) {
    args->valid[0] = 0;
    return;
  }
  query->best_t = t;
  query->best_triangle = triangle;
}

[[noreturn]] void fail(RTCDevice device, const char* what) {
  const RTCError e = device ? rtcGetDeviceError(device) : RTC_ERROR_UNKNOWN;
  throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(int(e)) + ")");
}

unsigned addSurface(RTCDevice device, RTCScene scene, const SurfaceMesh& mesh) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (!g) fail(device, "rtcNewGeometry");
  // Embree's own buffers (it may read 16 bytes past a vertex: it pads them).
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
  if (!vertices || !indices) {
    rtcReleaseGeometry(g);
    fail(device, "rtcSetNewGeometryBuffer");
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = mesh.positions[i][k];
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) indices[3 * i + k] = mesh.triangles[i][k];
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
  rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_MEDIUM);  // HIGH's spatial splits are not deterministic
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  const SurfaceMesh* surfaces[2] = {&source.rock, &source.colluvium};
  for (int i = 0; i < 2; ++i) {
    const SurfaceMesh& m = *surfaces[i];
    for (const auto& p : m.positions)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(p[k])), hi[k] = std::max(hi[k], double(p[k]));
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
    query.surface_geometry = s.geometry[surface];
    query.best_t = std::numeric_limits<float>::infinity();
    query.best_triangle = RTC_INVALID_GEOMETRY_ID;
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

bool RaySource::occluded(const std::array<float, 3>& origin, const std::array<float, 3>& direction, float start,
                         float reach) const {
  const Scene& s = *scene_;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = origin[0], ray.org_y = origin[1], ray.org_z = origin[2];
  ray.dir_x = direction[0], ray.dir_y = direction[1], ray.dir_z = direction[2];
  ray.tnear = start;
  ray.tfar = reach;
  ray.mask = 0xffffffffu;
  ray.time = 0.0f;
  ray.flags = 0;
  rtcOccluded1(s.scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree marks an occluded ray with tfar = −inf
}

}  // namespace rockbake
