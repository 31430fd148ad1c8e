// rockbake template "studio": a still with key, fill and rim lights over a
// neutral ground with a contact shadow. Placeholders (double-braced names): see README.md.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 5 }

#declare Rockbake_Finish = finish { ambient 0 diffuse 0.85 specular 0.05 roughness 0.05 }
#include "{{MESH_INCLUDE}}"

#declare Center = {{ASSET_CENTER}};
#declare Radius = {{ASSET_RADIUS}};

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
