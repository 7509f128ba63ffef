#include "sh/convolution.h"

#include <cmath>

namespace ddish::sh {

BandScales band_scales_from_zonal(const BandScales& zonal) {
  BandScales s{};
  for (int l = 0; l <= kMaxOrder; ++l)
    s[static_cast<std::size_t>(l)] =
        float(std::sqrt(4.0 * 3.14159265358979323846 / (2.0 * l + 1.0))) *
        zonal[static_cast<std::size_t>(l)];
  return s;
}

ShRgb convolve_bands(const ShRgb& f, const BandScales& band_scale) {
  ShRgb r = f;
  for (int i = 0; i < r.count(); ++i) r[i] *= band_scale[static_cast<std::size_t>(band_of(i))];
  return r;
}

ShRgb convolve_zonal(const ShRgb& f, const BandScales& zonal) {
  return convolve_bands(f, band_scales_from_zonal(zonal));
}

ShRgb irradiance_sh(const ShRgb& radiance) { return convolve_bands(radiance, kCosineLobe); }

glm::vec3 eval_convolved(const ShRgb& f, const glm::vec3& dir, const BandScales& band_scale) {
  float y[kMaxCoeffs];
  eval_basis(dir, f.order, y);
  glm::vec3 sum(0.0f);
  for (int l = 0; l <= f.order; ++l) {
    glm::vec3 band(0.0f);
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) band += f[i] * y[i];
    sum += band * band_scale[static_cast<std::size_t>(l)];
  }
  return sum;
}

glm::vec3 irradiance(const ShRgb& radiance, const glm::vec3& normal) {
  return eval_convolved(radiance, normal, kCosineLobe);
}

}  // namespace ddish::sh
