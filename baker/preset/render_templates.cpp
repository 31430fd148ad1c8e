#include "preset/render_templates.h"

#include <algorithm>
#include <cstdlib>

#include "preset/yaml_text.h"
#include "core/did_you_mean.h"

#ifndef ROCKBAKE_RENDER_TEMPLATES_DIR
#define ROCKBAKE_RENDER_TEMPLATES_DIR "render_templates"
#endif

namespace rockbake {

std::filesystem::path renderTemplatesDir() {
  const char* configured = std::getenv("ROCKBAKE_RENDER_TEMPLATES");
  return configured && *configured ? std::filesystem::path(configured)
                                   : std::filesystem::path(ROCKBAKE_RENDER_TEMPLATES_DIR);
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
  const std::string available =
      names.empty() ? "the folder " + dir.string() + " has none" : "available: " + joinNames(names);
  // Only a plain name can be looked up: nothing that climbs out of the folder or leaves it.
  if (!isAssetName(name)) return "'" + name + "' is not a template name; " + available;
  if (std::find(names.begin(), names.end(), name) != names.end()) return std::nullopt;
  const std::optional<std::string> best = closestName(name, names);
  return "no template '" + name + "'; " + (best ? "did you mean '" + *best + "'? " : std::string()) + available;
}

}  // namespace rockbake
