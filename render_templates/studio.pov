// rockbake template "studio": a still with key, fill and rim lights over a
// neutral ground with a contact shadow. Placeholders (double-braced names): see README.md.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 5 }

#declare Center = {{ASSET_CENTER}};
#declare Radius = {{ASSET_RADIUS}};

// The rock's texture set, where the bake made one: LOD0 with its base colour
// through its uvs and its height as a bump, as an engine gets it.
#declare Rockbake_Use_Maps = 1;
// Without one, the rock look made here (lengths follow the asset's size,
// patterns sampled at a seeded offset): colour varied within each layer at two
// scales, a bump at two scales (weathered wrinkles and sand grain), granular
// colluvium.
#declare Rockbake_Offset = {{SEED_OFFSET}};
#declare Rockbake_Finish = finish { ambient 0 diffuse 0.85 specular 0.03 roughness 0.08 }
#declare Rockbake_Dark = 0.78;
#declare Rockbake_Light = 1.12;
#declare Rockbake_Rock_Grain = pigment {
  average pigment_map {
    [3 granite turbulence 0.3 scale 0.25 * Radius translate Rockbake_Offset
       color_map { [0 rgb 0] [0.6 rgb 0.7] [1 rgb 1] }]
    [1 granite scale 0.02 * Radius translate 2 * Rockbake_Offset color_map { [0 rgb 0] [1 rgb 1] }]
  }
}
#declare Rockbake_Rock_Normal = normal {
  average normal_map {
    [2 wrinkles 0.9 scale 0.07 * Radius translate Rockbake_Offset]
    [1 granite 0.5 scale 0.012 * Radius translate 3 * Rockbake_Offset]
  }
}
#declare Rockbake_Colluvium_Grain = pigment {
  granite scale 0.015 * Radius translate 5 * Rockbake_Offset color_map { [0 rgb 0] [1 rgb 1] }
}
#declare Rockbake_Colluvium_Normal = normal {
  average normal_map {
    [1 crackle 0.8 scale 0.008 * Radius translate 7 * Rockbake_Offset]
    [1 granite 0.6 scale 0.004 * Radius translate 11 * Rockbake_Offset]
  }
}
#include "{{MESH_INCLUDE}}"

camera {
  perspective
  location {{CAMERA_LOCATION}}
  look_at {{CAMERA_LOOK_AT}}
  right x * image_width / image_height
  angle {{CAMERA_ANGLE}}
}

background { rgb <0.18, 0.18, 0.18> }

// POV-Ray is y-up: y is the world's z. The key light is high and to the
// camera's left, the fill low and opposite, the rim behind the asset
// (placed from the home camera, frame 0, so a turntable's lights stay put).
#declare Cam = {{CAMERA_HOME}} - Center;
#declare Fwd = vnormalize(<-Cam.x, 0, -Cam.z>);
#declare Side = vcross(y, Fwd);
light_source { Center + Radius * (-6 * Fwd - 4 * Side + 7 * y) color rgb <1.0, 0.96, 0.9> * 1.1
  area_light Radius * 1.5 * Side, Radius * 1.5 * y, 5, 5 adaptive 1 circular orient }
light_source { Center + Radius * (-5 * Fwd + 6 * Side + 1.5 * y) color rgb <0.75, 0.82, 1.0> * 0.3 shadowless }
light_source { Center + Radius * (6 * Fwd + 1 * Side + 5 * y) color rgb <1, 1, 1> * 0.7 }

plane {
  y, {{GROUND_Z}}
  pigment { rgb <0.18, 0.18, 0.18> }
  finish { ambient 0 diffuse 0.8 }
}

object { Rockbake_Rock }
#if (Rockbake_Has_Colluvium)
object { Rockbake_Colluvium }
#end
