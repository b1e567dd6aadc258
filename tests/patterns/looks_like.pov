// looks_like: the object at the light, casting no shadow
#version 3.7;
global_settings { assumed_gamma 1 }
camera { location <0,2,-6> look_at <0,0.5,0> }
plane { y, 0 pigment { checker rgb 1, rgb 0.5 } }
light_source { <1,2,0>, rgb 1 looks_like { sphere { 0, 0.3 pigment { rgb <1,1,0> } finish { ambient 1 } } } }
sphere { <-1,0.5,0>, 0.5 pigment { rgb <0,0,1> } }
