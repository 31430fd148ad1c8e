#include "preset/yaml_field.h"

namespace rockbake {

std::vector<InputError> unreadKeyProblems(const Source& source) {
  std::vector<InputError> problems;
  if (!source.reads) return problems;
  const ReadLog& reads = *source.reads;
  const auto stopped = [&](const std::string& map) {
    // The document's own keys are each asked for before anything below them is read.
    if (map.empty()) return false;
    return std::any_of(reads.failed.begin(), reads.failed.end(),
                       [&](const std::string& path) { return underKeyPath(path, map); });
  };
  const auto join = [](const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  };
  for (const auto& map : reads.maps) {
    if (!map.node.IsMap()) continue;
    // Where reading stopped, keys after the problem were never asked for: report only those that
    // look like misspellings of a key that was (a misspelt required key is what stops it, often).
    const bool partial = stopped(map.path);
    // Every key asked for here, present or not, in the order the reads asked: what the map may hold.
    std::vector<std::string> valid;
    const std::string prefix = map.path.empty() ? "" : map.path + ".";
    for (const auto& path : reads.asked_in_order)
      if (path.rfind(prefix, 0) == 0 && path.find('.', prefix.size()) == std::string::npos)
        valid.push_back(path.substr(prefix.size()));
    for (const auto& entry : map.node) {
      if (!entry.first.IsScalar()) continue;
      const std::string key = entry.first.Scalar();
      if (reads.asked.count(join(map.path, key))) continue;
      const Field bad(entry.first, join(map.path, key), source, map.mark);
      const std::optional<std::string> best = closestName(key, valid);
      // ...and only of a key the map lacks: beside a given 'points', 'joints' is no misspelling.
      if (partial && (!best || map.node[*best].IsDefined())) continue;
      problems.emplace_back(
          bad.location(), bad.path(),
          best ? "unknown key '" + key + "'; did you mean '" + *best + "'?" : "unknown key '" + key + "'",
          "valid keys here: " + joinNames(valid));
    }
  }
  return problems;
}

}  // namespace rockbake
