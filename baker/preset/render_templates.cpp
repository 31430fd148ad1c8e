#include "preset/render_templates.h"

#include <algorithm>
#include <cstdlib>

#include "core/did_you_mean.h"
#include "platform/data_dir.h"
#include "preset/yaml_text.h"

namespace rockbake {

std::filesystem::path renderTemplatesDir() {
  const char* configured = std::getenv("ROCKBAKE_RENDER_TEMPLATES");
  if (configured && *configured) return configured;
  return requireDataPath("render_templates");
}

std::vector<std::string> renderTemplateNames(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".pov" && isAssetName(entry.path().stem().string()))
      names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::optional<std::string> renderTemplateProblem(const std::string& name, const std::filesystem::path& dir) {
  const std::vector<std::string> names = renderTemplateNames(dir);
  std::error_code ec;
  const std::string available = !names.empty() ? "available: " + joinNames(names)
                                : std::filesystem::is_directory(dir, ec)
                                    ? "the folder " + dir.string() + " has none"
                                    : "the folder " + dir.string() + " does not exist";
  // Only a plain name can be looked up: nothing that climbs out of the folder or leaves it.
  if (!isAssetName(name)) return "'" + name + "' is not a template name; " + available;
  if (std::find(names.begin(), names.end(), name) != names.end()) return std::nullopt;
  const std::optional<std::string> best = closestName(name, names);
  return "no template '" + name + "'; " + (best ? "did you mean '" + *best + "'? " : std::string()) + available;
}

}  // namespace rockbake
