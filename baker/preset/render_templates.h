// Render templates are chosen by name, never by path (docs/preset-reference.md): a preset's
// `render.template` and `rockbake render --template` name a NAME.pov in the
// templates folder. That folder is render_templates/ in rockbake's data folder
// (platform/data_dir.h), or the folder the environment variable ROCKBAKE_RENDER_TEMPLATES
// names (a studio's own templates, configured explicitly by whoever runs rockbake).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rockbake {

// The templates folder, as above. Throws std::runtime_error (platform/data_dir.h's message)
// when ROCKBAKE_RENDER_TEMPLATES is unset and the data folder has no render_templates/.
std::filesystem::path renderTemplatesDir();

// The templates in `dir`: the stems of its .pov files, sorted.
std::vector<std::string> renderTemplateNames(const std::filesystem::path& dir);

// Why `name` names no template in `dir` ("'../x' is not a template name;
// available: debug, studio", "no template 'stuido'; did you mean 'studio'?
// available: ..."), or nothing when it names one. A name uses only a-z, 0-9,
// '_' and '-', at most 64 of them.
std::optional<std::string> renderTemplateProblem(const std::string& name, const std::filesystem::path& dir);

}  // namespace rockbake
