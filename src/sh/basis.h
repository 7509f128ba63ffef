// Real spherical harmonics (SH) basis, bands l = 0..4 (up to 25 functions).
//
// Convention, shared by every module that stores, packs or evaluates SH (probes, raster, net,
// and the GLSL shaders, which must mirror the formulas below):
//  - Orthonormal real SH over the unit sphere: the integral of Y_i * Y_j over the sphere is
//    delta_ij (no 4*pi or other factors folded in).
//  - Linear index i = l*(l+1) + m, m = -l..l; order L keeps bands 0..L, (L+1)^2 coefficients.
//  - Sign convention: no Condon-Shortley phase. Every function is a positive constant times the
//    polynomial written next to it, so Y_{1,-1} = +c*y, Y_{1,0} = +c*z, Y_{1,1} = +c*x.
//  - Directions are unit vec3 in ddish's world frame (+Y up) used as they are. The polar axis
//    of the formulas (the axis the m = 0 functions are symmetric about) is world +Z, not the up
//    axis: convolutions with zonal kernels (irradiance, GGX) are rotation invariant, so which
//    axis is polar never matters for shading, only for reading raw coefficients.
//  - The forms below use x^2 + y^2 + z^2 = 1 (e.g. 5z^2 - 1 instead of 4z^2 - x^2 - y^2), so the
//    direction must be normalised.
//
//   l=0:  0.2820948                  (1)
//   l=1:  0.4886025                  (y, z, x)
//   l=2:  1.0925484 xy, 1.0925484 yz, 0.3153916 (3z^2-1), 1.0925484 xz, 0.5462742 (x^2-y^2)
//   l=3:  0.5900436 y(3x^2-y^2), 2.8906114 xyz, 0.4570458 y(5z^2-1), 0.3731763 z(5z^2-3),
//         0.4570458 x(5z^2-1), 1.4453057 z(x^2-y^2), 0.5900436 x(x^2-3y^2)
//   l=4:  2.5033429 xy(x^2-y^2), 1.7701308 yz(3x^2-y^2), 0.9461747 xy(7z^2-1),
//         0.6690465 yz(7z^2-3), 0.1057855 (35z^4-30z^2+3), 0.6690465 xz(7z^2-3),
//         0.4730873 (x^2-y^2)(7z^2-1), 1.7701308 xz(x^2-3y^2), 0.6258357 (x^4-6x^2y^2+y^4)
#pragma once

#include <array>

#include <glm/vec3.hpp>

namespace ddish::sh {

inline constexpr int kMaxOrder = 4;
inline constexpr int kMaxCoeffs = 25;

// Number of coefficients of an order-L expansion (bands 0..L).
constexpr int coeff_count(int order) { return (order + 1) * (order + 1); }
// Linear index of Y_lm.
constexpr int sh_index(int l, int m) { return l * (l + 1) + m; }
// Band l of linear index i.
constexpr int band_of(int i) {
  int l = 0;
  while ((l + 1) * (l + 1) <= i) ++l;
  return l;
}

namespace detail {
// Normalisation constants, sqrt((2l+1)/(4 pi) (l-|m|)!/(l+|m|)!) times the factor that the
// polynomial form absorbs; printed to 17 digits so double evaluation is accurate too.
inline constexpr double kY00 = 0.28209479177387814;
inline constexpr double kY1 = 0.48860251190291992;
inline constexpr double kY2a = 1.0925484305920791;   // xy, yz, xz
inline constexpr double kY20 = 0.31539156525252001;
inline constexpr double kY22 = 0.54627421529603954;
inline constexpr double kY33 = 0.59004358992664351;
inline constexpr double kY3m2 = 2.8906114426405541;
inline constexpr double kY31 = 0.45704579946446574;
inline constexpr double kY30 = 0.37317633259011539;
inline constexpr double kY32 = 1.4453057213202770;
inline constexpr double kY4m4 = 2.5033429417967045;
inline constexpr double kY43 = 1.7701307697799305;
inline constexpr double kY4m2 = 0.94617469575756002;
inline constexpr double kY41 = 0.66904654355728917;
inline constexpr double kY40 = 0.10578554691520430;
inline constexpr double kY42 = 0.47308734787878001;
inline constexpr double kY44 = 0.62583573544917613;
}  // namespace detail

// Writes Y_0 .. Y_{(order+1)^2 - 1} at the unit direction d into out; order is clamped to
// 0..kMaxOrder. T is float or double.
template <typename T>
inline void eval_basis(const glm::vec<3, T>& d, int order, T* out) {
  using namespace detail;
  const T x = d.x, y = d.y, z = d.z;
  out[0] = T(kY00);
  if (order < 1) return;
  out[1] = T(kY1) * y;
  out[2] = T(kY1) * z;
  out[3] = T(kY1) * x;
  if (order < 2) return;
  const T x2 = x * x, y2 = y * y, z2 = z * z;
  out[4] = T(kY2a) * x * y;
  out[5] = T(kY2a) * y * z;
  out[6] = T(kY20) * (T(3) * z2 - T(1));
  out[7] = T(kY2a) * x * z;
  out[8] = T(kY22) * (x2 - y2);
  if (order < 3) return;
  out[9] = T(kY33) * y * (T(3) * x2 - y2);
  out[10] = T(kY3m2) * x * y * z;
  out[11] = T(kY31) * y * (T(5) * z2 - T(1));
  out[12] = T(kY30) * z * (T(5) * z2 - T(3));
  out[13] = T(kY31) * x * (T(5) * z2 - T(1));
  out[14] = T(kY32) * z * (x2 - y2);
  out[15] = T(kY33) * x * (x2 - T(3) * y2);
  if (order < 4) return;
  out[16] = T(kY4m4) * x * y * (x2 - y2);
  out[17] = T(kY43) * y * z * (T(3) * x2 - y2);
  out[18] = T(kY4m2) * x * y * (T(7) * z2 - T(1));
  out[19] = T(kY41) * y * z * (T(7) * z2 - T(3));
  out[20] = T(kY40) * (T(35) * z2 * z2 - T(30) * z2 + T(3));
  out[21] = T(kY41) * x * z * (T(7) * z2 - T(3));
  out[22] = T(kY42) * (x2 - y2) * (T(7) * z2 - T(1));
  out[23] = T(kY43) * x * z * (x2 - T(3) * y2);
  out[24] = T(kY44) * (x2 * x2 - T(6) * x2 * y2 + y2 * y2);
}

// Compile-time order: basis<2>(dir) returns the 9 L2 basis values.
template <int Order, typename T = float>
inline std::array<T, coeff_count(Order)> basis(const glm::vec<3, T>& d) {
  static_assert(Order >= 0 && Order <= kMaxOrder, "SH order must be 0..4");
  std::array<T, coeff_count(Order)> out;
  eval_basis(d, Order, out.data());
  return out;
}

}  // namespace ddish::sh
