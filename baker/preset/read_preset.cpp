#include "preset/read_preset.h"

#include "preset/schema_spec.h"

namespace rockbake {

Preset readPreset(const YAML::Node& root_node, Source& source, const std::filesystem::path& file) {
  ReadLog reads;
  source.reads = &reads;
  Preset p;
  p.file = file;
  const schema::ReadContext ctx{p, source};
  schema::readMap(schema::presetTable(), Field(root_node, "", source), p, nullptr, ctx);
  // A key no read asked for is unknown; it often explains a problem reported beside it.
  std::vector<InputError> unknown = unreadKeyProblems(source);
  source.problems->insert(source.problems->begin(), unknown.begin(), unknown.end());
  source.reads = nullptr;
  return p;
}

}  // namespace rockbake
