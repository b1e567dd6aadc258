// quilted, control0 and control1
#version 3.7;
global_settings { assumed_gamma 1 }
camera { orthographic location <0,0,-10> look_at <0,0,0> right 4*x up 3*y }
light_source { <-5,5,-10>, rgb 1 }
plane { z, 0 texture { pigment { quilted control0 0 control1 1 scale 0.5 color_map { [0 rgb 0] [1 rgb 1] } } finish { ambient 1 diffuse 0 } } }
