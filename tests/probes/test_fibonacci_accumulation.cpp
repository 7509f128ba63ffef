// The spherical Fibonacci lattice, random rotations, and the running-average weights.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "probes/accumulation.h"
#include "probes/fibonacci.h"

using namespace ddish::probes;

TEST(Fibonacci, UnitDirectionsWithZeroMeanAndIsotropicSecondMoment) {
  const std::uint32_t n = 256;
  glm::dvec3 mean(0.0);
  glm::dmat3 second(0.0);
  for (std::uint32_t i = 0; i < n; ++i) {
    glm::vec3 d = fibonacci_direction(i, n);
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-6f);
    mean += glm::dvec3(d);
    second += glm::outerProduct(glm::dvec3(d), glm::dvec3(d));
  }
  mean /= double(n);
  second /= double(n);
  // A uniform distribution on the sphere has mean 0 and E[d d^T] = I / 3. z is stratified
  // exactly (mean z = 0 to rounding); x and y follow the golden-angle spiral, equidistributed
  // to O(log n / n).
  EXPECT_NEAR(mean.z, 0.0, 1e-7);
  EXPECT_NEAR(mean.x, 0.0, 0.01);
  EXPECT_NEAR(mean.y, 0.0, 0.01);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(second[c][r], r == c ? 1.0 / 3.0 : 0.0, 0.01);
}

TEST(Fibonacci, RandomRotationIsOrthonormalAndSeedDetermined) {
  ddish::trace::Sampler a(7, 3, 1), b(7, 3, 1), c(8, 3, 1);
  glm::mat3 ra = random_rotation(a), rb = random_rotation(b), rc = random_rotation(c);
  EXPECT_EQ(ra, rb);
  EXPECT_NE(ra, rc);
  glm::mat3 i = glm::transpose(ra) * ra;
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col) EXPECT_NEAR(i[col][r], r == col ? 1.0f : 0.0f, 1e-5f);
  EXPECT_NEAR(glm::determinant(ra), 1.0f, 1e-5f);
}

TEST(Fibonacci, RandomRotationsAreUniform) {
  // The rotated north pole of a uniform rotation is uniform on the sphere: mean 0, E[z^2] = 1/3.
  const int n = 20000;
  glm::dvec3 mean(0.0);
  double zz = 0.0;
  for (int k = 0; k < n; ++k) {
    ddish::trace::Sampler s(1, std::uint64_t(k));
    glm::vec3 d = random_rotation(s) * glm::vec3(0.0f, 0.0f, 1.0f);
    mean += glm::dvec3(d);
    zz += double(d.z) * d.z;
  }
  // Standard error of a mean of n uniform coordinates: sqrt(1/3 / n) = 0.0041; allow 4 sigma.
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(mean[a] / n, 0.0, 0.017);
  EXPECT_NEAR(zz / n, 1.0 / 3.0, 0.012);
}

TEST(Accumulation, OneOverKThenHysteresis) {
  const float alpha = 0.9f;
  // 1/k >= 1 - alpha = 0.1 for k <= 10; exponential average afterwards.
  for (std::uint32_t k = 1; k <= 10; ++k) EXPECT_FLOAT_EQ(blend_weight(k, alpha), 1.0f / float(k));
  for (std::uint32_t k = 11; k <= 100; ++k) EXPECT_NEAR(blend_weight(k, alpha), 0.1f, 1e-7f);
  EXPECT_FLOAT_EQ(blend_weight(1, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(blend_weight(5, 0.0f), 1.0f);
  EXPECT_NO_THROW(check_hysteresis(0.0f));
  EXPECT_NO_THROW(check_hysteresis(kDefaultHysteresis));
  EXPECT_THROW(check_hysteresis(1.0f), std::invalid_argument);
  EXPECT_THROW(check_hysteresis(-0.1f), std::invalid_argument);
  EXPECT_THROW(check_hysteresis(std::nanf("")), std::invalid_argument);
}
