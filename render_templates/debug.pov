// rockbake template "debug": flat, shadowless lighting, so the rendered colour
// is exactly the palette colour (debug and curvature palettes). No ground; the
// background is black. Placeholders (double-braced names): see README.md.
#version 3.7;
global_settings { assumed_gamma 1.0 }

#declare Rockbake_Finish = finish { ambient 0 emission 1 diffuse 0 specular 0 }
#include "{{MESH_INCLUDE}}"

camera {
  perspective
  location {{CAMERA_LOCATION}}
  look_at {{CAMERA_LOOK_AT}}
  right x * image_width / image_height
  angle {{CAMERA_ANGLE}}
}

background { rgb 0 }

object { Rockbake_Rock }
#if (Rockbake_Has_Colluvium)
object { Rockbake_Colluvium }
#end
