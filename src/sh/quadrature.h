// Gauss-Legendre quadrature nodes and weights on [-1, 1]: exact for polynomials of degree
// 2n - 1, which makes SH integrals in cos(theta) exact with a handful of nodes.
#pragma once

#include <vector>

namespace ddish::sh {

struct GaussLegendre {
  std::vector<double> x;  // nodes, ascending
  std::vector<double> w;  // weights, summing to 2
};

// n >= 1 nodes, found by Newton iteration on the Legendre recurrence (accurate to ~1e-15).
GaussLegendre gauss_legendre(int n);

}  // namespace ddish::sh
