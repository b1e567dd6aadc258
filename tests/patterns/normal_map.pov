// normal_map
#version 3.7;
global_settings { assumed_gamma 1 }
camera { orthographic location <0,0,-10> look_at <0,0,0> right 4*x up 3*y }
light_source { <-5,5,-10>, rgb 1 }
plane { z, 0 texture { pigment { rgb 0.8 } normal { gradient x normal_map { [0.3 bumps 0.5 scale 0.2] [0.7 ripples 0.8] } scale 1.3 } finish { ambient 0.1 diffuse 0.9 } } }
