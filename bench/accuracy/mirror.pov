// SPDX-License-Identifier: MIT
// mirror.pov: refs scene A (tests/accuracy/mirror.scn) for POV-Ray 3.7 with
// photons, for bench/accuracy. An isotropic point light at (0,1,0), a mirror
// in the plane x = 1 (0 <= y <= 2, |z| <= 2, reflectance 1, facing -x: the
// -x face of a thin black box), a white diffuse floor at y = 0.
//   Declare=Count=N   global photons `count` (0: photons off)
//   Declare=Radius=R  gather radius (default 0.05, as bench/caustics)
//   Declare=Gmax=M    most photons per gather (default 100, POV's default)
// The image is the reflected light alone, seen straight down: the
// orthographic camera maps x in [-3, 1] (columns, left to right) and z in
// [4, -4] (rows, top to bottom) onto a 1:2 image (+W400 +H800: pixels of
// 0.01, ten a side per 0.1 reference cell). It sits at y = 0.5, below the
// light and beside the mirror, which it never sees. An invisible opaque
// sheet just above the floor, which photons pass through, blocks every
// shadow ray, so the floor holds no direct light: its value is the photon
// irradiance estimate x diffuse 1, in POV-Ray's own units (bench/accuracy
// scales it to the exact flux).
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
camera { orthographic location <-1, 0.5, 0> direction <0, -1, 0> up <0, 0, 8> right <4, 0, 0> }
// A POV-Ray photon carries its light's colour x (path length)^2 x the fade
// factor 2/(1 + (path/fade_distance)^fade_power) (photons.cpp,
// addSurfacePhoton); fade_power 2 with a tiny fade_distance cancels the
// path^2, so every photon carries the same energy, as a physical point light's
// (bench/caustics/sphere.pov measured the tilt without it).
light_source { <0, 1, 0>, rgb 5000 fade_distance 0.01 fade_power 2 }
box { <1, 0, -2>, <1.05, 2, 2>
  pigment { rgb 0 }
  finish { ambient 0 diffuse 0 specular 0 reflection 1 }
  photons { target  reflection on  refraction off }
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
