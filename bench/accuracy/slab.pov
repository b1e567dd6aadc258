// SPDX-License-Identifier: MIT
// slab.pov: refs scene C (tests/accuracy/slab.scn) for POV-Ray 3.7 with
// photons, for bench/accuracy. An isotropic point light at (0,2,0), a glass
// slab 0.5 <= y <= 1 (a 10 x 10 box, ior 1.5, ideal transmission: no
// reflection, no Fresnel), a white diffuse floor at y = 0.
//   Declare=Count=N   global photons `count` (0: photons off)
//   Declare=Radius=R  gather radius (default 0.05, as bench/caustics)
//   Declare=Gmax=M    most photons per gather (default 100, POV's default)
// The image is the light through the slab alone, seen straight down: the
// orthographic camera maps the square x, z in [-3, 3] onto the whole image
// (pixel centre (i + 0.5) * 6/W - 3) from y = 0.25, below the slab (eye rays
// start there and never see it). An invisible opaque sheet just above the
// floor, which photons pass through, blocks every shadow ray (POV-Ray's
// shadow rays would pass the clear glass), so the floor holds no direct
// light: its value is the photon irradiance estimate x diffuse 1, in
// POV-Ray's own units (bench/accuracy scales it to the exact flux).
#version 3.7;
#ifndef (Count) #declare Count = 100000; #end
#ifndef (Radius) #declare Radius = 0.05; #end
#ifndef (Gmax) #declare Gmax = 100; #end
global_settings {
  assumed_gamma 1
  max_trace_level 10
  #if (Count > 0)
    photons { count Count  radius Radius  jitter 0.4  gather 20, Gmax }
  #end
}
camera { orthographic location <0, 0.25, 0> direction <0, -1, 0> up <0, 0, 6> right <6, 0, 0> }
// Every photon carries the same energy (see mirror.pov: the fade cancels
// POV-Ray's path^2 factor).
light_source { <0, 2, 0>, rgb 5000 fade_distance 0.01 fade_power 2 }
box { <-5, 0.5, -5>, <5, 1, 5>
  pigment { rgbf 1 }
  finish { ambient 0 diffuse 0 specular 0 reflection 0 }
  interior { ior 1.5 }
  photons { target  refraction on  reflection off }
}
// The shadow sheet: blocks direct light on the floor, invisible, ignored by photons.
box { <-1000, 0.001, -1000>, <1000, 0.002, 1000>
  pigment { rgb 0 }
  photons { pass_through collect off }
  no_image no_reflection
}
plane { y, 0
  pigment { rgb 1 }
  finish { ambient 0 diffuse 1 specular 0 }
}
