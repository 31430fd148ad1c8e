// Blender asset catalogues for `rockbake blender-library` (docs/libraries.md, "Blender's asset
// browser"): one catalogue per preset (a library entry's name, or a plain bake's preset name),
// and one per wedge beneath it, written to the library's blender_assets.cats.txt in Blender's
// format:
//
//   VERSION 1
//   <uuid>:<catalogue/path>:<simple name>
//
// Each UUID is derived from its catalogue path alone (the first 16 bytes of
// SHA-256("rockbake blender catalogue:" + path), marked as an RFC 9562 version-8 UUID), so
// the same catalogues give the same file on every run and every machine, and an asset's
// catalogue ID can be recomputed from its path.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace rockbake {

inline constexpr const char* kBlenderCatalogFile = "blender_assets.cats.txt";

struct BlenderCatalog {
  std::string path;         // "goblin", "goblin/tall"
  std::string uuid;         // 8-4-4-4-12 lower-case hex digits
  std::string simple_name;  // the path with '/' as '-', as Blender makes it
};

// The catalogue an asset belongs to, from its manifest's inputs: a library job's entry name (its
// job name less "-<wedge>" and "-s<seed>") with "/<wedge>" for a wedge; a plain bake's name.
std::string catalogPathForJob(const nlohmann::json& manifest_inputs);

std::string catalogUuid(const std::string& path);
BlenderCatalog blenderCatalog(const std::string& path);

// Every catalogue the paths name and every parent of one ("goblin" for "goblin/tall"), once each,
// sorted by path.
std::vector<BlenderCatalog> catalogsWithParents(const std::vector<std::string>& paths);

// blender_assets.cats.txt's text for `catalogs`, in their order.
std::string catalogFileText(const std::vector<BlenderCatalog>& catalogs);

}  // namespace rockbake
