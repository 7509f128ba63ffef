#include <cmath>

#include <gtest/gtest.h>

#include "sh/quadrature.h"

namespace ddish::sh {
namespace {

TEST(GaussLegendre, IntegratesPolynomialsExactly) {
  for (int n : {1, 2, 5, 16, 33}) {
    const GaussLegendre q = gauss_legendre(n);
    ASSERT_EQ(q.x.size(), std::size_t(n));
    for (int deg = 0; deg <= 2 * n - 1; ++deg) {
      double s = 0.0;
      for (int i = 0; i < n; ++i) s += q.w[std::size_t(i)] * std::pow(q.x[std::size_t(i)], deg);
      const double exact = deg % 2 ? 0.0 : 2.0 / (deg + 1);
      EXPECT_NEAR(s, exact, 1e-13) << "n=" << n << " degree " << deg;
    }
    for (int i = 1; i < n; ++i) EXPECT_LT(q.x[std::size_t(i - 1)], q.x[std::size_t(i)]);
  }
}

}  // namespace
}  // namespace ddish::sh
