/* SPDX-License-Identifier: MIT */
/* spectrum.h: the spectral maths of `passes spectral` (docs/spectral.md):
 * the CIE 1931 2° observer, the conversion of a wavelength's light to the
 * working space (linear Rec.709, D65), the wavelengths light rays and eye
 * paths sample, and the dispersion law that gives each its index.
 *
 * Contract:
 *  - spec_cie is the multi-lobe Gaussian fit of Wyman, Sloan and Shirley
 *    (JCGT 2(2), 2013) to the CIE 1931 2° colour matching functions: no
 *    tables. Summed at 1 nm over 360–830 nm it gives 106.77, 106.92, 106.88
 *    for x̄, ȳ, z̄ (the CIE tables: 106.87, 106.86, 106.89), within 0.1 %.
 *  - spec_xyz_to_rgb takes XYZ to linear Rec.709 with the equal-energy
 *    spectrum as white (Bradford adaptation from illuminant E to D65, then
 *    the Rec.709 matrix): a flat spectrum is neutral, r = g = b, as an RGB
 *    white light is.
 *  - spec_weights gives, per channel c, a weight w_c(λ) ≥ 0 with
 *    ∫ w_c dλ = 1 over [SPEC_MIN, SPEC_MAX]: how channel c of a light's
 *    energy is spread over the spectrum. It is the colour of light at λ
 *    (spec_xyz_to_rgb of the observer at λ, over ∫ȳ) moved into the gamut
 *    by adding white where a channel is negative (the lobes of a spectral
 *    colour outside Rec.709): w(λ) = (k(λ) + a(λ)·(1,1,1)) / (1 + ∫a), with
 *    a(λ) = max(0, −min_c k_c(λ)). Adding white keeps the hue of every
 *    wavelength (the RGB hue depends only on channel differences); one
 *    common scale keeps each channel's area 1, so an equal-energy white
 *    stays (1,1,1) and light of RGB colour E spread as E_c·w_c(λ) carries
 *    exactly E_c per channel. The cost is saturation: the spectral colours
 *    come out at ~1/1.7 of their out-of-gamut chroma.
 *  - spec_sample maps u in [0,1) to a wavelength drawn with density
 *    p(λ) ∝ (w_R + w_G + w_B)(λ), piecewise constant over 1 nm bins, and
 *    returns the factors f_c = w_c(λ)/p(λ): for u uniform, E[f_c] = 1 per
 *    channel, and f_R + f_G + f_B ≈ 3 for every ray (only the colour varies).
 *    Stratified u give stratified wavelengths (the map is monotonic).
 *  - spec_ior is Cauchy's law n(λ) = A + B/λ², chosen so that the light of
 *    each channel refracts, on average, as the RGB passes' convention has it
 *    (red ior/√D, green ior, blue ior·√D): the mean index of channel c's
 *    light, ∫ w_c(λ) n(λ) dλ = A + B·⟨1/λ²⟩_c, is ior for green, and blue's
 *    is D times red's. That is, n(λ̄_G) = ior and n(λ̄_B)/n(λ̄_R) = D at the
 *    channels' centroids λ̄_c = ⟨1/λ²⟩_c^(−1/2) (spec_centroid: about 583,
 *    532 and 467 nm). A prism then puts each RGB pass's band where that
 *    channel's share of the spectral pass's rainbow is centred, and the
 *    rainbow runs on past them: n(400 nm)/n(700 nm) ≈ 1 + 2.6·(D − 1).
 *
 * All functions are pure and thread-safe (the tables are built once, on
 * first use, under pthread_once). */
#ifndef ARVO_SPECTRUM_H
#define ARVO_SPECTRUM_H

#define SPEC_MIN 360.0    /* nm: the observer's range, where wavelengths are drawn */
#define SPEC_MAX 830.0

/* The CIE 1931 2° colour matching functions x̄, ȳ, z̄ at lambda (nm). */
void spec_cie(double lambda, double xyz[3]);
/* XYZ to linear Rec.709 (D65), equal-energy white to r = g = b. */
void spec_xyz_to_rgb(const double xyz[3], double rgb[3]);
/* The unclipped colour of light at lambda: spec_xyz_to_rgb(spec_cie) / ∫ȳ
 * (each channel integrates to about 1; some are negative). */
void spec_colour(double lambda, double k[3]);
/* The per-channel weights w_c(lambda) ≥ 0 (1/nm), ∫ w_c dλ = 1. */
void spec_weights(double lambda, double w[3]);
/* The wavelength for u in [0,1) and its factors f_c = w_c/p (see above). */
double spec_sample(double u, double f[3]);
/* The density p(lambda) (1/nm) spec_sample draws with. */
double spec_pdf(double lambda);
/* The centroid wavelength λ̄_c (nm) of channel c's weight, in 1/λ². */
double spec_centroid(int c);
/* The index of refraction at lambda (nm) of a medium of index ior and
 * dispersion D (see above); ior itself when D = 1. */
double spec_ior(double ior, double D, double lambda);

#endif
