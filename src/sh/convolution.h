// Convolution of an SH function with a zonal (axially symmetric) kernel, and irradiance.
//
// For a kernel h(w . n) with zonal coefficients h_l = h_{l0} (its SH coefficients when its axis
// is the polar axis), the convolution (f * h)(n) = integral of f(w) h(w . n) dw has coefficients
//   (f * h)_lm = sqrt(4 pi / (2l+1)) h_l f_lm                     (Funk-Hecke theorem),
// so a zonal convolution is one scale per band: band_scale[l] = sqrt(4 pi / (2l+1)) h_l.
//
// Irradiance (Ramamoorthi & Hanrahan 2001): the clamped cosine max(w . n, 0) has band scales
//   A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4, A_3 = 0, A_4 = -pi / 24,
// so E(n) = sum A_l L_lm Y_lm(n) for radiance coefficients L_lm. Radiance in, irradiance out:
// a constant radiance L gives E = pi L; the Lambertian outgoing radiance is albedo / pi * E.
#pragma once

#include <array>
#include <span>

#include <glm/vec3.hpp>

#include "sh/sh_rgb.h"

namespace ddish::sh {

using BandScales = std::array<float, kMaxOrder + 1>;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr BandScales kCosineLobe = {kPi, 2.0f * kPi / 3.0f, kPi / 4.0f, 0.0f,
                                           -kPi / 24.0f};

// band_scale[l] = sqrt(4 pi / (2l+1)) * zonal[l]: from a kernel's zonal coefficients.
BandScales band_scales_from_zonal(const BandScales& zonal);

// f_lm * band_scale[l] for every coefficient (the convolution, or any per-band filter).
ShRgb convolve_bands(const ShRgb& f, const BandScales& band_scale);
// Convolution with the kernel whose zonal coefficients (SH of the kernel about the polar axis,
// m = 0 only) are zonal[l].
ShRgb convolve_zonal(const ShRgb& f, const BandScales& zonal);

// Irradiance SH (the cosine convolution of the radiance), and irradiance at a unit normal.
ShRgb irradiance_sh(const ShRgb& radiance);
glm::vec3 irradiance(const ShRgb& radiance, const glm::vec3& normal);

// sum band_scale[l] f_lm Y_lm(dir): a convolved function evaluated without building it.
glm::vec3 eval_convolved(const ShRgb& f, const glm::vec3& dir, const BandScales& band_scale);

}  // namespace ddish::sh
