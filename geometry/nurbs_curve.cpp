// NURBS curves (thesis 5.6; The NURBS Book 4.2 and A4.2).
#include "geometry/nurbs_curve.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "geometry/bspline_basis.hpp"

namespace isomuscle::geometry {

// Checks counts and that every point is finite and every weight finite and positive.
NurbsCurve::NurbsCurve(KnotVector knots, std::vector<Eigen::Vector3d> points,
                       std::vector<double> weights)
    : knots_(std::move(knots)), points_(std::move(points)), weights_(std::move(weights)) {
  const std::size_t n = static_cast<std::size_t>(knots_.num_basis());
  if (knots_.size() == 0) {
    throw std::invalid_argument("NurbsCurve: empty knot vector");
  }
  if (points_.size() != n || weights_.size() != n) {
    throw std::invalid_argument("NurbsCurve: the knot vector (" + std::to_string(knots_.size()) +
                                " knots, degree " + std::to_string(knots_.degree()) + ") needs " +
                                std::to_string(n) + " control points and weights, got " +
                                std::to_string(points_.size()) + " points and " +
                                std::to_string(weights_.size()) + " weights");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!points_[i].allFinite()) {
      throw std::invalid_argument("NurbsCurve: control point " + std::to_string(i) +
                                  " is not finite");
    }
    if (!(std::isfinite(weights_[i]) && weights_[i] > 0.0)) {
      throw std::invalid_argument("NurbsCurve: weight " + std::to_string(i) + " = " +
                                  std::to_string(weights_[i]) + " must be finite and positive");
    }
  }
}

bool NurbsCurve::is_rational() const {
  for (double w : weights_) {
    if (w != weights_.front()) {
      return true;
    }
  }
  return false;
}

// C(u) = sum N_i w_i P_i / sum N_i w_i (thesis 5.6). Units of the control points.
Eigen::Vector3d NurbsCurve::evaluate(double u) const {
  const int p = knots_.degree();
  const int span = knots_.find_span(u);
  double N[kMaxDegree + 1];
  basis_functions(knots_, span, u, N);
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  double w = 0.0;
  for (int j = 0; j <= p; ++j) {
    const int i = span - p + j;
    const double nw = N[j] * weights_[i];
    a.noalias() += nw * points_[i];
    w += nw;
  }
  return a / w;
}

// C' = (A' - w' C) / w with A = sum N_i w_i P_i, w = sum N_i w_i (NURBS Book eq. 4.8).
Eigen::Vector3d NurbsCurve::derivative(double u) const {
  return derivatives(u, 1)[1];
}

// C^(k) = (A^(k) - sum_{i=1..k} binom(k,i) w^(i) C^(k-i)) / w (NURBS Book eq. 4.8, A4.2). Units:
// control-point units / [u]^k.
std::vector<Eigen::Vector3d> NurbsCurve::derivatives(double u, int n) const {
  if (n < 0) {
    throw std::invalid_argument("NurbsCurve::derivatives: order " + std::to_string(n) +
                                " must be >= 0");
  }
  const int p = knots_.degree();
  const int span = knots_.find_span(u);
  std::vector<double> dN(static_cast<std::size_t>((n + 1) * (p + 1)));
  basis_derivatives(knots_, span, u, n, dN.data());
  std::vector<Eigen::Vector3d> A(static_cast<std::size_t>(n + 1), Eigen::Vector3d::Zero());
  std::vector<double> W(static_cast<std::size_t>(n + 1), 0.0);
  for (int k = 0; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) {
      const int i = span - p + j;
      const double nw = dN[static_cast<std::size_t>(k * (p + 1) + j)] * weights_[i];
      A[k].noalias() += nw * points_[i];
      W[k] += nw;
    }
  }
  std::vector<Eigen::Vector3d> C(static_cast<std::size_t>(n + 1));
  for (int k = 0; k <= n; ++k) {
    Eigen::Vector3d v = A[k];
    double binom = 1.0;
    for (int i = 1; i <= k; ++i) {
      binom = binom * static_cast<double>(k - i + 1) / static_cast<double>(i);
      v.noalias() -= binom * W[i] * C[k - i];
    }
    C[k] = v / W[0];
  }
  return C;
}

}  // namespace isomuscle::geometry
