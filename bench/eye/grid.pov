// SPDX-License-Identifier: MIT
// grid.pov: the POV-Ray 3.7 copy of grid.scn; only the light differs (as in spheres.pov).
#ifndef (N) #declare N = 100000; #end
#declare S = ceil(pow(N, 1 / 3) - 1e-6);
#declare Step = 10 / S;
#declare R = 0.4 * Step;
camera { location <5, 5, -20> look_at <5, 5, 5> angle 50 }
light_source { <-10, 30, -30>, rgb 2000 / pi fade_distance 0.7071 fade_power 2 }
background { rgb <0.05, 0.05, 0.08> }
#declare Count = 0;
#declare K = 0;
#while (K < S & Count < N)
  #declare J = 0;
  #while (J < S & Count < N)
    #declare I = 0;
    #while (I < S & Count < N)
      sphere { <I, J, K> * Step, R
        pigment { rgb <I / S, J / S, 0.5 + 0.5 * sin(K * 0.3)> } finish { ambient 0.05 diffuse 0.8 } }
      #declare Count = Count + 1;
      #declare I = I + 1;
    #end
    #declare J = J + 1;
  #end
  #declare K = K + 1;
#end
