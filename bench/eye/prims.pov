// SPDX-License-Identifier: MIT
// prims.pov: the POV-Ray 3.7 copy of prims.scn; only the lights differ (POV fading 2/(1+2d²) ≈ 1/d² and no 1/π in its diffuse, so both images look alike).
// alike (prims.pov is the same file): a checker floor, a mirror sphere, a
// glass sphere, a glass box, a torus, a cone and a cylinder under two point
// lights. No #version: arvo's physical model (timing does not depend on it).
camera { location <0, 3, -8> look_at <0, 1, 0> angle 50 }
light_source { <-4, 8, -5>, rgb 80 / pi fade_distance 0.7071 fade_power 2 }
light_source { <5, 6, -2>, rgb 40 / pi fade_distance 0.7071 fade_power 2 }
background { rgb <0.05, 0.06, 0.08> }
plane { y, 0 pigment { checker rgb 1 rgb 0.2 } finish { ambient 0 diffuse 0.8 reflection 0.1 } }
sphere { <-2.2, 1, 0>, 1 pigment { rgb 0.9 } finish { ambient 0 diffuse 0.1 reflection 0.85 specular 0.5 } }
sphere { <0, 1, -1>, 1 pigment { rgbf <1, 1, 1, 0.95> }
  finish { ambient 0 diffuse 0 specular 0.6 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy }
  interior { ior 1.5 } }
box { <1.2, 0, -0.5>, <3, 1.6, 1.2> pigment { rgbf <0.8, 1, 0.9, 0.9> }
  finish { ambient 0 diffuse 0.05 reflection 0.1 } interior { ior 1.33 } }
torus { 0.8, 0.25 rotate 60 * x translate <-0.5, 0.9, 2.5> pigment { rgb <0.9, 0.6, 0.2> }
  finish { ambient 0 diffuse 0.7 phong 0.6 reflection 0.3 } }
cone { <2.5, 0, 3>, 0.8, <2.5, 2, 3>, 0 pigment { rgb <0.3, 0.5, 0.9> } finish { ambient 0 diffuse 0.8 } }
cylinder { <-3.5, 0, 3>, <-3.5, 2.5, 3>, 0.4 pigment { rgb <0.5, 0.9, 0.4> } finish { ambient 0 diffuse 0.8 reflection 0.2 } }
