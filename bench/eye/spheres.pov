// SPDX-License-Identifier: MIT
// spheres.pov: the POV-Ray 3.7 copy of spheres.scn; only the light differs (as in prims.pov).
// 3.7 alike (spheres.pov is the same file): N small diffuse spheres (default
// 100,000; -D N=… / Declare=N=…) at random in a 40 × 40 × 40 box, their
// radius shrinking as N grows so the box stays about equally full, seen
// from outside under one light.
#ifndef (N) #declare N = 100000; #end
#declare R = 0.6 * pow(1000 / N, 1 / 3);
#declare S = seed(7);
camera { location <0, 30, -70> look_at <0, 0, 0> angle 50 }
light_source { <-40, 80, -60>, rgb 9000 / pi fade_distance 0.7071 fade_power 2 }
background { rgb <0.05, 0.06, 0.08> }
#declare I = 0;
#while (I < N)
  sphere { <rand(S) - 0.5, rand(S) - 0.5, rand(S) - 0.5> * 40, R
    pigment { rgb <rand(S), 0.5, 0.8> } finish { ambient 0.05 diffuse 0.8 } }
  #declare I = I + 1;
#end
