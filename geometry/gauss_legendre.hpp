#pragma once
// Gauss–Legendre quadrature on [-1, 1]: n points integrate polynomials of degree 2n - 1 exactly
// (Abramowitz & Stegun 25.4.29; nodes by Newton iteration on the Legendre polynomial P_n). The one
// rule of the project: volume measures here, tensor rules of knot-span elements (iga) and the
// collapsed rules of tetrahedra (tet) are all built from it.
#include <vector>

namespace isomuscle::geometry {

struct GaussLegendreRule {
  std::vector<double> points;   // abscissae in (-1, 1), ascending
  std::vector<double> weights;  // positive, summing to 2
};

// Largest number of points accepted by gauss_legendre_rule().
inline constexpr int kMaxGaussLegendrePoints = 64;

// n-point rule on [-1, 1]; throws std::invalid_argument unless 1 <= n <= kMaxGaussLegendrePoints.
GaussLegendreRule gauss_legendre_rule(int n);

}  // namespace isomuscle::geometry
