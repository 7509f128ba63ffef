// Real spherical harmonics L0-L4 in GLSL, the same basis as src/sh/basis.h (read its header
// for the convention): orthonormal, no Condon-Shortley phase, index l(l+1)+m, polar axis +Z,
// and the polynomial forms that assume a unit direction. Any change here must follow basis.h,
// which the CPU side (probe tracer, packing, tests) uses; tests/raster compares the two.
#ifndef DDISH_SH_BASIS_GLSL
#define DDISH_SH_BASIS_GLSL

const int SH_MAX_ORDER = 4;
const int SH_MAX_COEFFS = 25;

// (order + 1)^2: coefficients of bands 0..order.
#define SH_COEFF_COUNT(order) (((order) + 1) * ((order) + 1))

// Writes Y_0 .. Y_{(order+1)^2 - 1} at the unit direction d into y and zero past them. `order`
// is a compile-time constant at every call in ddish, so the driver drops the unused bands.
void sh_basis(vec3 d, int order, out float y[SH_MAX_COEFFS]) {
  for (int i = 0; i < SH_MAX_COEFFS; ++i) y[i] = 0.0;
  const float x = d.x, yy = d.y, z = d.z;
  y[0] = 0.28209479177387814;
  if (order < 1) return;
  y[1] = 0.48860251190291992 * yy;
  y[2] = 0.48860251190291992 * z;
  y[3] = 0.48860251190291992 * x;
  if (order < 2) return;
  const float x2 = x * x, y2 = yy * yy, z2 = z * z;
  y[4] = 1.0925484305920791 * x * yy;
  y[5] = 1.0925484305920791 * yy * z;
  y[6] = 0.31539156525252001 * (3.0 * z2 - 1.0);
  y[7] = 1.0925484305920791 * x * z;
  y[8] = 0.54627421529603954 * (x2 - y2);
  if (order < 3) return;
  y[9] = 0.59004358992664351 * yy * (3.0 * x2 - y2);
  y[10] = 2.8906114426405541 * x * yy * z;
  y[11] = 0.45704579946446574 * yy * (5.0 * z2 - 1.0);
  y[12] = 0.37317633259011539 * z * (5.0 * z2 - 3.0);
  y[13] = 0.45704579946446574 * x * (5.0 * z2 - 1.0);
  y[14] = 1.4453057213202770 * z * (x2 - y2);
  y[15] = 0.59004358992664351 * x * (x2 - 3.0 * y2);
  if (order < 4) return;
  y[16] = 2.5033429417967045 * x * yy * (x2 - y2);
  y[17] = 1.7701307697799305 * yy * z * (3.0 * x2 - y2);
  y[18] = 0.94617469575756002 * x * yy * (7.0 * z2 - 1.0);
  y[19] = 0.66904654355728917 * yy * z * (7.0 * z2 - 3.0);
  y[20] = 0.10578554691520430 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0);
  y[21] = 0.66904654355728917 * x * z * (7.0 * z2 - 3.0);
  y[22] = 0.47308734787878001 * (x2 - y2) * (7.0 * z2 - 1.0);
  y[23] = 1.7701307697799305 * x * z * (x2 - 3.0 * y2);
  y[24] = 0.62583573544917613 * (x2 * x2 - 6.0 * x2 * y2 + y2 * y2);
}

// Band l of linear index i (i < 25).
int sh_band(int i) { return i < 1 ? 0 : (i < 4 ? 1 : (i < 9 ? 2 : (i < 16 ? 3 : 4))); }

#endif  // DDISH_SH_BASIS_GLSL
