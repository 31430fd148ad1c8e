// The delivery profile (docs/delivery.md): what the preset's `delivery.profile` makes of the
// asset's files, as plain data for the stages that write them.
//
//   profile   meshes and nodes        materials         maps' files          normal maps   hulls          GLB images
//   generic   rock_lod0               <name>_rock       <name>_BaseColor…    OpenGL        collision.naming  files
//   unreal    SM_<name>_rock_lod0     M_<name>_rock     T_<name>_BaseColor…  DirectX       UCX_            embedded
//   godot     <name>_rock_lod0        <name>_rock       <name>_BaseColor…    OpenGL        -convcolonly    embedded
//   unity     <name>_rock_lod0        <name>_rock       <name>_BaseColor…    OpenGL        collision.naming  embedded
//
// DirectX normal maps are the files in textures/ (green down, as Unreal's texture importer
// reads them); the GLBs embed them with green turned back, as glTF requires OpenGL's. Every profile writes
// the GLBs in metres (units_per_meter).
#pragma once

#include <string>

#include "export/glb_file.h"
#include "preset/preset.h"

namespace rockbake {

struct DeliveryConventions {
  GlbConventions glb;  // names, unit and images of every GLB and collision.glb
  HullNaming hull_naming = HullNaming::Unreal;
  std::string texture_name;      // the texture set's <name>: "goblin", or "T_goblin"
  bool directx_normals = false;  // textures/' normal maps hold green down (glb.directx_normal_files too)
};

// The conventions of `preset`'s profile for an asset written to `asset_dir`.
DeliveryConventions deliveryConventions(const Preset& preset, const std::filesystem::path& asset_dir);

}  // namespace rockbake
