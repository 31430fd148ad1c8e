#include "pipeline/delivery_profile.h"

namespace rockbake {

DeliveryConventions deliveryConventions(const Preset& preset, const std::filesystem::path& asset_dir) {
  DeliveryConventions c;
  const std::string& name = preset.name;
  c.glb.meters_per_unit = 1.0 / preset.units_per_meter;
  c.glb.image_folder = asset_dir;
  c.glb.material_prefix = name + "_";  // two assets in one scene keep their own materials
  c.hull_naming = preset.collision.naming;
  c.texture_name = name;
  switch (preset.delivery.profile) {
    case DeliveryProfile::Generic:
      break;
    case DeliveryProfile::Unreal:
      // Unreal's naming conventions: SM_ static meshes, M_ materials, T_ textures, UCX_ hulls.
      c.glb.mesh_prefix = "SM_" + name + "_";
      c.glb.material_prefix = "M_" + name + "_";
      c.texture_name = "T_" + name;
      c.hull_naming = HullNaming::Unreal;
      c.directx_normals = c.glb.directx_normal_files = true;
      c.glb.embed_images = true;
      break;
    case DeliveryProfile::Godot:
      c.glb.mesh_prefix = name + "_";
      c.hull_naming = HullNaming::Godot;
      c.glb.embed_images = true;
      break;
    case DeliveryProfile::Unity:
      c.glb.mesh_prefix = name + "_";
      c.glb.embed_images = true;
      break;
  }
  return c;
}

}  // namespace rockbake
