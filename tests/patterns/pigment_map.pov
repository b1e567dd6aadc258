// pigment_map, transformed
#version 3.7;
global_settings { assumed_gamma 1 }
camera { orthographic location <0,0,-10> look_at <0,0,0> right 4*x up 3*y }
light_source { <-5,5,-10>, rgb 1 }
plane { z, 0 texture { pigment { gradient x pigment_map { [0.2 checker rgb 1, rgb <1,0,0> scale 0.2] [0.8 bozo scale 0.2] } scale 1.5 rotate 20*z } finish { ambient 1 diffuse 0 } } }
