// texture_map: a finish and a normal in one entry
#version 3.7;
global_settings { assumed_gamma 1 }
camera { orthographic location <0,0,-10> look_at <0,0,0> right 4*x up 3*y }
light_source { <-5,5,-10>, rgb 1 }
plane { z, 0 texture { gradient x texture_map { [0.3 pigment { bozo scale 0.2 } finish { ambient 1 diffuse 0 }] [0.7 pigment { rgb <1,0,0> } finish { ambient 0.2 diffuse 0.8 } normal { bumps 0.5 scale 0.1 }] } scale 1.5 } }
