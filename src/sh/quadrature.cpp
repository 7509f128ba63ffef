#include "sh/quadrature.h"

#include <cmath>

namespace ddish::sh {

GaussLegendre gauss_legendre(int n) {
  GaussLegendre q;
  if (n < 1) n = 1;
  q.x.resize(static_cast<std::size_t>(n));
  q.w.resize(static_cast<std::size_t>(n));
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Chebyshev-like first guess of the i-th largest root; Newton converges in a few steps.
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      // P_n'(x) = n (x P_n - P_{n-1}) / (x^2 - 1)
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    const auto lo = static_cast<std::size_t>(i);
    const auto hi = static_cast<std::size_t>(n - 1 - i);
    q.x[lo] = -x;
    q.x[hi] = x;
    q.w[lo] = w;
    q.w[hi] = w;
  }
  return q;
}

}  // namespace ddish::sh
