// tiles { textures tile2 textures }: POV-Ray's old checker of textures
#version 3.7;
global_settings { assumed_gamma 1 }
camera { orthographic location <0,0,-10> look_at <0,0,0> right 4*x up 3*y }
light_source { <-5,5,-10>, rgb 1 }
plane { z, 0 texture { tiles { texture { pigment { granite scale 0.5 } finish { ambient 1 diffuse 0 } } tile2 texture { pigment { rgb <0,0,1> } } texture { pigment { bozo scale 0.2 color_map { [0.5 rgbt <1,0,0,0>] [0.5 rgbt 1] } } } } scale 0.7 } }
