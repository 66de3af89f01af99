#pragma once
// Gauss–Legendre quadrature on an interval: n points integrate polynomials of degree 2n - 1 exactly
// (Golub & Welsch 1969; here by Newton iteration on the Legendre polynomial P_n, Abramowitz &
// Stegun 25.4.29). Used per parametric direction to build the tensor rule of a knot-span element.
#include <vector>

namespace isomuscle::iga {

struct GaussRule {
  std::vector<double> points;   // abscissae in (-1, 1), ascending
  std::vector<double> weights;  // positive, summing to 2
};

// Largest number of points per direction accepted by gauss_legendre().
inline constexpr int kMaxGaussPoints = 32;

// n-point rule on [-1, 1]; throws std::invalid_argument unless 1 <= n <= kMaxGaussPoints.
GaussRule gauss_legendre(int n);

}  // namespace isomuscle::iga
