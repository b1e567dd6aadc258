// layered textures: declared texture { } texture { } texture { }
#version 3.7;
global_settings { assumed_gamma 1 }
camera { orthographic location <0,0,-10> look_at <0,0,0> right 4*x up 3*y }
light_source { <-5,5,-10>, rgb 1 }
#declare T = texture { pigment { rgb <0.2,0.4,0.9> } finish { ambient 0.2 diffuse 0.7 } }
  texture { pigment { bozo scale 0.4 color_map { [0.4 rgbt <1,0.5,0,0>] [0.6 rgbt <1,1,1,1>] } } finish { ambient 0.3 diffuse 0.6 phong 0.5 } }
  texture { pigment { gradient x color_map { [0 rgbf <0,1,0,0.8>] [0.5 rgbt 1] } } }
plane { z, 0 texture { T } }
