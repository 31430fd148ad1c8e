#include "preset/yaml_text.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include "core/error.h"

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

std::string joinNamesWith(const std::vector<std::string>& names, const std::string& conjunction) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " " + conjunction + " " : ", ") + names[i];
  return out;
}

bool isAssetName(const std::string& name) {
  return !assetNameProblem(name);
}

std::optional<std::string> assetNameProblem(const std::string& name) {
  const bool allowed = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
  const std::string shown = name.size() > 24 ? name.substr(0, 20) + "..." : name;
  if (!allowed) return "'" + shown + "' may only use a-z, 0-9, '_' and '-'";
  if (name.size() > kMaxNameLength)
    return "'" + shown + "' is " + std::to_string(name.size()) + " characters long; at most " +
           std::to_string(kMaxNameLength) + " are allowed";
  return std::nullopt;
}

namespace {

// Only where each document starts: enough to find a second one.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;
  std::vector<YAML::Mark> first_nodes;  // where each document's first value is
  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override { node(mark); }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnMapEnd() override {}

 private:
  void node(const YAML::Mark& mark) {
    if (first_nodes.size() < starts.size()) first_nodes.push_back(mark);
  }
};

}  // namespace

YAML::Node loadYamlDocument(const std::string& text, const std::string& file, const std::string& what) {
  int line = 1, column = 1;
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\t' && c != '\n' && c != '\r') || byte == 0x7f)
      throw InputError({file, line, column}, "", "a control byte (" + escapeControlBytes(std::string(1, c)) + ") here",
                       "YAML is text: remove it, or write it as an escape inside a double-quoted string");
    if (c == '\n')
      ++line, column = 1;
    else
      ++column;
  }
  const auto at = [&](const YAML::Mark& mark) -> SourceLocation {
    if (mark.is_null()) return {file, 0, 0};
    return {file, mark.line + 1, mark.column + 1};
  };
  try {
    // Find where documents start, stopping at the second: yaml-cpp 0.7's LoadAll loops for ever (allocating
    // as it goes) on text it cannot move past, such as a leading ','. There each "document" starts where
    // the one before did.
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentStarts documents;
    while (documents.starts.size() < 2 && parser.HandleNextDocument(documents)) {
    }
    if (documents.starts.size() == 2) {
      const YAML::Mark& second = documents.starts[1];
      if (second.pos == documents.starts[0].pos)
        throw InputError(at(second), "", "malformed YAML: a value cannot start with what is here",
                         "check the indentation and brackets there");
      const YAML::Mark& second_value = documents.first_nodes.size() > 1 ? documents.first_nodes[1] : second;
      throw InputError(at(second_value), "", what + " holds one YAML document; a second one starts here",
                       "remove the '---' and what follows");
    }
    return YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw InputError(at(e.mark), "", "nested more than " + std::to_string(e.depth() - 1) + " levels deep",
                     "is this the right file?");
  } catch (const YAML::Exception& e) {
    throw InputError(at(e.mark), "", "malformed YAML: " + e.msg, "check the indentation and brackets there");
  }
}

std::optional<std::string> readYamlFile(const std::string& file, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!ec && size > kMaxYamlFileBytes)
    throw InputError({file}, "",
                     "the file is " + std::to_string(size) + " bytes; " + what + " is at most " +
                         std::to_string(kMaxYamlFileBytes >> 20) + " MiB",
                     "is this the right file?");
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rockbake
