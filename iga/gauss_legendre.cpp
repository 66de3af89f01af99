#include "iga/gauss_legendre.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace isomuscle::iga {

// Nodes are the roots of P_n, found by Newton from the Chebyshev-like guess
// cos(pi (i + 3/4) / (n + 1/2)); weights w_i = 2 / ((1 - x_i^2) P_n'(x_i)^2) (A&S 25.4.29).
// P_n and P_n' come from the three-term recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}.
GaussRule gauss_legendre(int n) {
  if (n < 1 || n > kMaxGaussPoints) {
    throw std::invalid_argument("gauss_legendre: number of points " + std::to_string(n) +
                                " outside the valid range 1.." + std::to_string(kMaxGaussPoints));
  }
  GaussRule rule;
  rule.points.assign(n, 0.0);
  rule.weights.assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0;
      double p1 = x;
      for (int k = 1; k < n; ++k) {
        const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) {
        break;
      }
    }
    // Recompute the derivative at the converged root for the weight.
    double p0 = 1.0;
    double p1 = x;
    for (int k = 1; k < n; ++k) {
      const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
      p0 = p1;
      p1 = p2;
    }
    dp = n * (x * p1 - p0) / (x * x - 1.0);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.points[i] = -x;
    rule.points[n - 1 - i] = x;
    rule.weights[i] = w;
    rule.weights[n - 1 - i] = w;
  }
  if (n % 2 == 1) {
    rule.points[n / 2] = 0.0;  // exact midpoint
  }
  return rule;
}

}  // namespace isomuscle::iga
