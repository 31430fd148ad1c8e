#include "pipeline/bake_timings.h"

namespace rockbake {

nlohmann::ordered_json bakeTimingsJson(const BakeTimings& t) {
  nlohmann::ordered_json stages;
  stages["load"] = t.load;
  stages["shape"] = t.shape;
  stages["simulate"] = t.simulate;
  stages["simulate_curvature"] = t.simulate_curvature;
  stages["simulate_colluvium"] = t.simulate_colluvium;
  stages["simulate_rockfall"] = t.simulate_rockfall;
  if (t.mesh) {
    stages["mesh_extract"] = t.mesh->extract;
    stages["mesh_subdivide"] = t.mesh->subdivide;
    stages["mesh_attributes"] = t.mesh->attributes;
    stages["mesh_simplify"] = t.mesh->simplify;
    if (t.mesh->clasts) stages["clasts"] = *t.mesh->clasts;
  }
  if (t.texture) stages["texture"] = *t.texture;
  if (t.mesh) stages["export"] = t.mesh->exports;
  if (t.write_vdb) stages["write_vdb"] = *t.write_vdb;
  if (t.collision) stages["collision"] = *t.collision;
  if (t.render) stages["render"] = *t.render;
  stages["total"] = t.total;
  return stages;
}

}  // namespace rockbake
