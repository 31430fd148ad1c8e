#include "preset/yaml_text.h"

#include <algorithm>

#include <yaml-cpp/yaml.h>

namespace rockbake {

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Null:
      return "nothing (null)";
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    default:
      return "nothing";
  }
}

std::optional<std::uint64_t> unsignedValue(const YAML::Node& node) {
  if (!node.IsScalar() || node.Scalar().empty() || node.Scalar()[0] == '-') return std::nullopt;
  try {
    return node.as<std::uint64_t>();
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

bool isAssetName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

}  // namespace rockbake
