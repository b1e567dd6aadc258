// SPDX-License-Identifier: MIT
// sphere.pov: refs scene B (tests/accuracy/sphere.scn) for POV-Ray 3.7 with
// photons, for bench/caustics. A point light at (0,10,0), a glass sphere
// (r 1, ior 1.5, ideal transmission: no reflection, no Fresnel) centred at
// (0,3,0), a white diffuse floor at y = 0.
//   Declare=Count=N   global photons `count` (0: photons off); POV-Ray 3.7
//                     shoots about N/3 photons here and stores about 2N/3
//   Declare=Radius=R  gather radius (default 0.05: smaller speckles, jitter 0 rings)
//   Declare=Gmax=M    most photons per gather (default 100, POV's default)
// The image is the caustic alone, seen straight down: the orthographic camera
// maps the square x, z in [-3, 3] onto the whole image (pixel centre (i + 0.5)
// · 6/W - 3), the camera sits at y = 1.5, below the sphere (eye rays start
// there and never see it; no_image would also hide it from photons), and an
// invisible opaque sheet just above
// the floor that photons pass through blocks every shadow ray, so the floor
// holds no direct light: its value is the photon irradiance estimate × diffuse
// 1, in POV-Ray's own units (normalise by total flux to compare).
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
camera { orthographic location <0, 1.5, 0> direction <0, -1, 0> up <0, 0, 6> right <6, 0, 0> }
// POV-Ray attenuates photons by the light's fade over their whole path: without fade
// the floor profile tilts (+25 % at r = 3 against the centre, measured);
// fade_power 2 with a tiny fade_distance is 1/d² to 1e-6 (2·5000·0.01² = 1).
light_source { <0, 10, 0>, rgb 5000 fade_distance 0.01 fade_power 2 }
sphere { <0, 3, 0>, 1
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
