// rockbake template "turntable": the studio set-up (key, fill, rim, ground with
// contact shadow) while the camera circles the world z axis. The baker renders
// this once per frame ({{FRAME}} of {{FRAMES}}, {{TURNTABLE_ANGLE}} degrees) and
// moves only the camera; the lights stay fixed to the ground, placed from the
// home camera. With {{LOOKDEV}} = 1 (render.turntable.lookdev) an 18 % grey
// ball and a 24-patch colour chart ride with the camera in the lower corners,
// as on a look-dev turntable, so every frame shows the light the rock gets.
// Placeholders (double-braced names): see README.md.
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

// The look-dev set: camera-fixed, casting no shadow on the rock or the ground.
#if ({{LOOKDEV}})
#declare Lookdev_Eye = {{CAMERA_LOCATION}};
#declare Lookdev_Fwd = vnormalize({{CAMERA_LOOK_AT}} - Lookdev_Eye);
#declare Lookdev_Right = vnormalize(vcross(y, Lookdev_Fwd));
#declare Lookdev_Up = vcross(Lookdev_Fwd, Lookdev_Right);
// A plane across the view at 40 % of the way to the asset, and the half-width
// and half-height of the picture there.
#declare Lookdev_Depth = 0.4 * vlength({{CAMERA_LOOK_AT}} - Lookdev_Eye);
#declare Lookdev_HalfW = Lookdev_Depth * tan(radians({{CAMERA_ANGLE}}) / 2);
#declare Lookdev_HalfH = Lookdev_HalfW * image_height / image_width;
#declare Lookdev_Frame = transform {
  matrix <Lookdev_Right.x, Lookdev_Right.y, Lookdev_Right.z,
          Lookdev_Up.x, Lookdev_Up.y, Lookdev_Up.z,
          Lookdev_Fwd.x, Lookdev_Fwd.y, Lookdev_Fwd.z,
          Lookdev_Eye.x, Lookdev_Eye.y, Lookdev_Eye.z>
}
#declare Lookdev_Matte = finish { ambient 0 diffuse 1 specular 0 }
// 18 % grey (scene-linear albedo 0.18), lower right.
#declare Lookdev_Ball = 0.16 * Lookdev_HalfH;
sphere {
  <Lookdev_HalfW - 1.4 * Lookdev_Ball, -Lookdev_HalfH + 1.4 * Lookdev_Ball, Lookdev_Depth>, Lookdev_Ball
  pigment { rgb 0.18 } finish { Lookdev_Matte }
  transform { Lookdev_Frame } no_shadow
}
// The chart, lower left: the 24 patches of the classic colour checker (its
// published sRGB values, turned scene-linear), on a black card, six by four.
#declare Lookdev_Linear = function(C) { select(C / 255 - 0.04045, C / 255 / 12.92, C / 255 / 12.92,
                                                 pow((C / 255 + 0.055) / 1.055, 2.4)) }
#declare Lookdev_Patches = array[24] {
  <115, 82, 68>, <194, 150, 130>, <98, 122, 157>,
  <87, 108, 67>, <133, 128, 177>, <103, 189, 170>,
  <214, 126, 44>, <80, 91, 166>, <193, 90, 99>,
  <94, 60, 108>, <157, 188, 64>, <224, 163, 46>,
  <56, 61, 150>, <70, 148, 73>, <175, 54, 60>,
  <231, 199, 31>, <187, 86, 149>, <8, 133, 161>,
  <243, 243, 242>, <200, 200, 200>, <160, 160, 160>,
  <122, 122, 121>, <85, 85, 85>, <52, 52, 52>
}
#declare Lookdev_Cell = 0.085 * Lookdev_HalfH;
#declare Lookdev_Chart_X = -Lookdev_HalfW + 0.6 * Lookdev_Cell;
#declare Lookdev_Chart_Y = -Lookdev_HalfH + 0.6 * Lookdev_Cell;
union {
  box { <-0.15, -0.15, 0.01> * Lookdev_Cell, <6.15, 4.15, 0.02> * Lookdev_Cell pigment { rgb 0.01 } finish { Lookdev_Matte } }
  #for (Row, 0, 3)
    #for (Col, 0, 5)
      box {
        <Col + 0.08, 3 - Row + 0.08, 0> * Lookdev_Cell, <Col + 0.92, 3 - Row + 0.92, 0.01> * Lookdev_Cell
        #local C = Lookdev_Patches[Row * 6 + Col];
        pigment { rgb <Lookdev_Linear(C.x), Lookdev_Linear(C.y), Lookdev_Linear(C.z)> } finish { Lookdev_Matte }
      }
    #end
  #end
  translate <Lookdev_Chart_X, Lookdev_Chart_Y, Lookdev_Depth>
  transform { Lookdev_Frame } no_shadow
}
#end
