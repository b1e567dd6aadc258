// number_of_waves 3: waves as a pigment, ripples as a normal
#version 3.7;
global_settings { assumed_gamma 1 number_of_waves 3 }
camera { orthographic location <0,0,-10> look_at <0,0,0> right 4*x up 3*y }
light_source { <-5,5,-10>, rgb 1 }
plane { z, 0 texture { pigment { waves color_map { [0 rgb 0] [1 rgb 1] } } finish { ambient 1 diffuse 0 } } }
plane { z, 0 texture { pigment { rgb 0.8 } normal { ripples 0.6 } finish { ambient 0.1 diffuse 0.9 } } translate <2,0,-0.01> }
