// normal bumps, transformed
#version 3.7;
global_settings { assumed_gamma 1 }
camera { orthographic location <0,0,-10> look_at <0,0,0> right 4*x up 3*y }
light_source { <-5,5,-10>, rgb 1 }
plane { z, 0 texture { pigment { rgb 0.8 } normal { bumps 0.5 scale 0.2 rotate 30*z translate x } finish { ambient 0.1 diffuse 0.9 } } }
