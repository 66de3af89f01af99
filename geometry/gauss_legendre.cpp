#include "geometry/gauss_legendre.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace isomuscle::geometry {

namespace {

// P_n(x) and P_n'(x) by the three-term recurrence (k + 1) P_{k+1} = (2k + 1) x P_k - k P_{k-1},
// P_n' = n (x P_n - P_{n-1}) / (x^2 - 1) (Abramowitz & Stegun 22.7.10, 22.8.5).
void legendre(int n, double x, double& p, double& dp) {
  double p0 = 1.0;
  double p1 = x;
  for (int k = 1; k < n; ++k) {
    const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
    p0 = p1;
    p1 = p2;
  }
  p = p1;
  dp = n * (x * p1 - p0) / (x * x - 1.0);
}

}  // namespace

// Nodes are the roots of P_n, found by Newton from the guess cos(pi (i + 3/4) / (n + 1/2));
// weights w_i = 2 / ((1 - x_i^2) P_n'(x_i)^2) (Abramowitz & Stegun 25.4.29), with P_n' from the
// last Newton iterate (it differs from the root by less than 1e-16).
GaussLegendreRule gauss_legendre_rule(int n) {
  if (n < 1 || n > kMaxGaussLegendrePoints) {
    throw std::invalid_argument("gauss_legendre_rule: number of points " + std::to_string(n) +
                                " outside the valid range 1.." +
                                std::to_string(kMaxGaussLegendrePoints));
  }
  GaussLegendreRule rule;
  rule.points.assign(static_cast<std::size_t>(n), 0.0);
  rule.weights.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double p = 0.0;
    double dp = 0.0;
    for (int iter = 0; iter < 100; ++iter) {
      legendre(n, x, p, dp);
      const double dx = p / dp;
      x -= dx;
      if (std::abs(dx) <= 1e-16) {
        break;
      }
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.points[static_cast<std::size_t>(i)] = -x;
    rule.points[static_cast<std::size_t>(n - 1 - i)] = x;
    rule.weights[static_cast<std::size_t>(i)] = w;
    rule.weights[static_cast<std::size_t>(n - 1 - i)] = w;
  }
  if (n % 2 == 1) {
    rule.points[static_cast<std::size_t>(n / 2)] = 0.0;  // exact midpoint
  }
  return rule;
}

}  // namespace isomuscle::geometry
