// The SH basis: orthonormality by exact quadrature, and agreement (values and signs) with an
// independent evaluation from associated Legendre functions.
#include <cmath>
#include <random>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "sh/basis.h"
#include "sh/quadrature.h"

namespace ddish::sh {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Real SH from the textbook definition, phase chosen as documented in basis.h:
// Y_lm = sqrt(2) K_l|m| P_l^|m|(cos theta) {cos(m phi) | sin(|m| phi)}, with P_l^m without the
// Condon-Shortley (-1)^m, theta measured from +Z and phi from +X towards +Y.
double legendre_p(int l, int m, double x) {
  // P_m^m = (2m-1)!! (1-x^2)^(m/2), then the upward recurrence in l.
  double pmm = 1.0;
  const double s = std::sqrt(std::max(0.0, 1.0 - x * x));
  for (int i = 1; i <= m; ++i) pmm *= (2.0 * i - 1.0) * s;
  if (l == m) return pmm;
  double pm1 = x * (2.0 * m + 1.0) * pmm;
  if (l == m + 1) return pm1;
  double p = 0.0;
  for (int k = m + 2; k <= l; ++k) {
    p = ((2.0 * k - 1.0) * x * pm1 - (k + m - 1.0) * pmm) / (k - m);
    pmm = pm1;
    pm1 = p;
  }
  return p;
}

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

double reference_y(int l, int m, const glm::dvec3& d) {
  const int am = std::abs(m);
  const double k = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi) * factorial(l - am) / factorial(l + am));
  const double phi = std::atan2(d.y, d.x);
  const double p = legendre_p(l, am, d.z);
  if (m == 0) return k * p;
  return std::sqrt(2.0) * k * p * (m > 0 ? std::cos(m * phi) : std::sin(am * phi));
}

TEST(ShBasis, IndexHelpers) {
  EXPECT_EQ(coeff_count(0), 1);
  EXPECT_EQ(coeff_count(2), 9);
  EXPECT_EQ(coeff_count(4), 25);
  EXPECT_EQ(sh_index(0, 0), 0);
  EXPECT_EQ(sh_index(1, -1), 1);
  EXPECT_EQ(sh_index(2, 0), 6);
  EXPECT_EQ(sh_index(4, 4), 24);
  for (int l = 0; l <= 4; ++l)
    for (int m = -l; m <= l; ++m) EXPECT_EQ(band_of(sh_index(l, m)), l);
}

// Gauss-Legendre in cos(theta) (12 nodes: exact to degree 23) times a uniform phi grid (32
// steps: exact for trigonometric degree < 32) integrates every product Y_i Y_j (degree <= 8)
// exactly, so the only error left is float rounding of the basis values.
TEST(ShBasis, OrthonormalByQuadrature) {
  const GaussLegendre gl = gauss_legendre(12);
  const int nphi = 32;
  double gram[kMaxCoeffs][kMaxCoeffs] = {};
  for (std::size_t a = 0; a < gl.x.size(); ++a) {
    const double z = gl.x[a];
    const double s = std::sqrt(1.0 - z * z);
    for (int p = 0; p < nphi; ++p) {
      const double phi = 2.0 * kPi * (p + 0.5) / nphi;
      const glm::vec3 d(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
      float y[kMaxCoeffs];
      eval_basis(glm::normalize(d), 4, y);
      const double w = gl.w[a] * 2.0 * kPi / nphi;
      for (int i = 0; i < kMaxCoeffs; ++i)
        for (int j = 0; j < kMaxCoeffs; ++j) gram[i][j] += w * double(y[i]) * double(y[j]);
    }
  }
  double worst = 0.0;
  for (int i = 0; i < kMaxCoeffs; ++i)
    for (int j = 0; j < kMaxCoeffs; ++j)
      worst = std::max(worst, std::fabs(gram[i][j] - (i == j ? 1.0 : 0.0)));
  std::printf("[sh] orthonormality L0-L4: max |<Yi,Yj> - delta_ij| = %.2e\n", worst);
  EXPECT_LT(worst, 1e-5);
}

TEST(ShBasis, MatchesAssociatedLegendreDefinition) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  double worst = 0.0;
  for (int k = 0; k < 500; ++k) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
    double y[kMaxCoeffs];
    eval_basis(d, 4, y);
    for (int l = 0; l <= 4; ++l)
      for (int m = -l; m <= l; ++m)
        worst = std::max(worst, std::fabs(y[sh_index(l, m)] - reference_y(l, m, d)));
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(ShBasis, SignConventionAndOrderParameter) {
  // Y_{1,-1}, Y_{1,0}, Y_{1,1} are positive along +Y, +Z, +X.
  const auto by = basis<1>(glm::vec3(0, 1, 0));
  const auto bz = basis<1>(glm::vec3(0, 0, 1));
  const auto bx = basis<1>(glm::vec3(1, 0, 0));
  EXPECT_GT(by[1], 0.48f);
  EXPECT_GT(bz[2], 0.48f);
  EXPECT_GT(bx[3], 0.48f);
  // A lower order writes only its own coefficients.
  float y[kMaxCoeffs];
  for (float& v : y) v = -99.0f;
  eval_basis(glm::vec3(0, 0, 1), 2, y);
  EXPECT_NEAR(y[6], 0.6307831f, 1e-6f);  // 2 * 0.3153916 at the pole
  EXPECT_EQ(y[9], -99.0f);
  const auto b4 = basis<4>(glm::vec3(0.0f, 0.6f, 0.8f));
  const auto b2 = basis<2>(glm::vec3(0.0f, 0.6f, 0.8f));
  for (int i = 0; i < 9; ++i) EXPECT_EQ(b4[std::size_t(i)], b2[std::size_t(i)]);
}

}  // namespace
}  // namespace ddish::sh
