#include "preset/preset_json.h"

#include "preset/schema_spec.h"

namespace rockbake {

nlohmann::json presetToJson(const Preset& p) {
  return schema::writeMap(schema::presetTable(), p);
}

}  // namespace rockbake
