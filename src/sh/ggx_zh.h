// Zonal-harmonic (ZH) coefficients of the GGX specular lobe, for shading glossy reflections
// from SH probes (DDISH-GI; Ikkala 2020, appendix A).
//
// The lobe. For glTF roughness r (GGX alpha = r^2), view along the normal (v = n), the lobe
// over the reflected direction l, with h the half vector of v and l, is
//   g(l) = D(h) (n . l) / 4      for n . l > 0, else 0,
// that is the GGX NDF pushed through the reflection mapping (D (n.h) / (4 (v.h)), where
// n.h = v.h here) times the cosine at l. It is symmetric about n, so it has only zonal
// coefficients; they are normalised so band 0 is 1:
//   k_l = integral g(l) P_l(n . l) dl / integral g(l) dl,   k = (1, k_1, k_2, k_3, k_4).
// As band scales, k turns radiance SH into the lobe-weighted average radiance about the
// reflection direction R: sum_l k_l sum_m L_lm Y_lm(R) (the "prefiltered radiance" of the
// split-sum approximation; the raster multiplies it by its own specular DFG term).
// Roughness 0 is a delta (k = 1 in every band); roughness 1 makes D constant and g the clamped
// cosine, k = (1, 2/3, 1/4, 0, -1/24).
//
// Where this comes from: the thesis text itself was not available to this project; the fit
// was read from Tauray (the thesis's renderer, shader/spherical_harmonics.glsl,
// get_ggx_specular_lobe, called with sqrt(alpha) = glTF roughness), whose comment points to an
// integration script that was not available either. The lobe above was identified by
// integrating candidates and comparing with the fit: it agrees within 2.2e-4 in every band
// (largest at r = 0, where the fit overshoots 1), whereas the bare NDF D about the reflection
// direction, D(h)(n.h) pushed to the reflected direction without the cosine, or that lobe with
// Smith masking differ from the fit by 0.1 or more at some roughness (ggx_zh_test.cpp).
#pragma once

#include <array>

#include <glm/vec3.hpp>

#include "sh/convolution.h"
#include "sh/sh_rgb.h"

namespace ddish::sh {

// Direct numerical integration (composite Gauss-Legendre in tan(theta_h), panels that double
// in width from alpha/8, so narrow and wide lobes are resolved alike); accurate to float
// precision (the result is rounded to float).
BandScales ggx_zh_integrate(float roughness);

// The project's table: k_l at roughness j / (kGgxZhNodes - 1), j = 0..kGgxZhNodes-1, filled
// by ggx_zh_integrate on first use, interpolated by 4-point (cubic) Lagrange. Its error
// against direct integration is below 5e-6 (checked in tests/sh/ggx_zh_test.cpp); it is
// largest near r = 0.005, where the GGX tail makes k_l behave like 1 - c r^4 log r.
inline constexpr int kGgxZhNodes = 65;
using GgxZhTable = std::array<BandScales, kGgxZhNodes>;
const GgxZhTable& ggx_zh_table();  // thread-safe; for uploading to shaders
BandScales ggx_zh(float roughness);

// The closed-form fit in roughness published with DDISH-GI (Ikkala 2020, appendix A, as used
// in Tauray): k_l = a + b cos(c r + d) + b' cos(c' r + d') + r (f / sqrt(e + r^2) + g), with
// fitted constants per band. Band 0 is 1. Kept for comparison and for shaders that want it.
BandScales ggx_zh_ikkala_fit(float roughness);

// Lobe-weighted average of the radiance SH about the unit reflection direction.
glm::vec3 ggx_specular(const ShRgb& radiance, const glm::vec3& reflect_dir, float roughness);

}  // namespace ddish::sh
