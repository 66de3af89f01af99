// NURBS surfaces (thesis 5.11; The NURBS Book 4.4).
#include "geometry/nurbs_surface.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "geometry/bspline_basis.hpp"

namespace isomuscle::geometry {

// Checks counts (n_u n_v points and weights, index i + n_u j) and finiteness/positivity.
NurbsSurface::NurbsSurface(KnotVector u, KnotVector v, std::vector<Eigen::Vector3d> points,
                           std::vector<double> weights)
    : u_(std::move(u)), v_(std::move(v)), points_(std::move(points)), weights_(std::move(weights)) {
  if (u_.size() == 0 || v_.size() == 0) {
    throw std::invalid_argument("NurbsSurface: empty knot vector in " +
                                std::string(u_.size() == 0 ? "u" : "v"));
  }
  const std::size_t n = static_cast<std::size_t>(count_u()) * static_cast<std::size_t>(count_v());
  if (points_.size() != n || weights_.size() != n) {
    throw std::invalid_argument("NurbsSurface: the knot vectors need " + std::to_string(count_u()) +
                                " x " + std::to_string(count_v()) + " = " + std::to_string(n) +
                                " control points and weights, got " +
                                std::to_string(points_.size()) + " points and " +
                                std::to_string(weights_.size()) + " weights");
  }
  for (std::size_t a = 0; a < n; ++a) {
    const int i = static_cast<int>(a) % count_u();
    const int j = static_cast<int>(a) / count_u();
    const std::string where = " (" + std::to_string(i) + ", " + std::to_string(j) + ")";
    if (!points_[a].allFinite()) {
      throw std::invalid_argument("NurbsSurface: control point" + where + " is not finite");
    }
    if (!(std::isfinite(weights_[a]) && weights_[a] > 0.0)) {
      throw std::invalid_argument("NurbsSurface: weight" + where + " = " +
                                  std::to_string(weights_[a]) + " must be finite and positive");
    }
  }
}

bool NurbsSurface::is_rational() const {
  for (double w : weights_) {
    if (w != weights_.front()) {
      return true;
    }
  }
  return false;
}

// S(u,v) = sum_ij N_i N_j w_ij P_ij / sum_ij N_i N_j w_ij (thesis 5.11).
Eigen::Vector3d NurbsSurface::evaluate(double u, double v) const {
  Eigen::Vector3d point;
  Eigen::Matrix<double, 3, 2> d;
  evaluate_derivatives(u, v, point, d);
  return point;
}

// First partials by the quotient rule on the homogeneous sums A = sum N w P, W = sum N w:
// S_,a = (A_,a - W_,a S) / W (NURBS Book eq. 4.20). Units: point units / [parameter].
void NurbsSurface::evaluate_derivatives(double u, double v, Eigen::Vector3d& point,
                                        Eigen::Matrix<double, 3, 2>& d) const {
  const int p = u_.degree();
  const int q = v_.degree();
  const int su = u_.find_span(u);
  const int sv = v_.find_span(v);
  double Nu[2 * (kMaxDegree + 1)];
  double Nv[2 * (kMaxDegree + 1)];
  basis_first_derivatives(u_, su, u, Nu);
  basis_first_derivatives(v_, sv, v, Nv);
  Eigen::Vector3d A = Eigen::Vector3d::Zero();
  Eigen::Vector3d Au = Eigen::Vector3d::Zero();
  Eigen::Vector3d Av = Eigen::Vector3d::Zero();
  double W = 0.0;
  double Wu = 0.0;
  double Wv = 0.0;
  for (int b = 0; b <= q; ++b) {
    const int j = sv - q + b;
    for (int a = 0; a <= p; ++a) {
      const int i = su - p + a;
      const int idx = i + count_u() * j;
      const double w = weights_[idx];
      const double n00 = Nu[a] * Nv[b] * w;
      const double n10 = Nu[p + 1 + a] * Nv[b] * w;
      const double n01 = Nu[a] * Nv[q + 1 + b] * w;
      A.noalias() += n00 * points_[idx];
      Au.noalias() += n10 * points_[idx];
      Av.noalias() += n01 * points_[idx];
      W += n00;
      Wu += n10;
      Wv += n01;
    }
  }
  point = A / W;
  d.col(0) = (Au - Wu * point) / W;
  d.col(1) = (Av - Wv * point) / W;
}

// Compares the first and last control rows in direction dir, relative to the bounding-box diagonal.
bool NurbsSurface::is_closed(int dir, double tol) const {
  if (dir != 0 && dir != 1) {
    throw std::invalid_argument("NurbsSurface::is_closed: direction " + std::to_string(dir) +
                                " must be 0 (u) or 1 (v)");
  }
  Eigen::Vector3d lo = points_.front();
  Eigen::Vector3d hi = points_.front();
  for (const Eigen::Vector3d& x : points_) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double limit = tol * (hi - lo).norm();
  const int nu = count_u();
  const int nv = count_v();
  if (dir == 0) {
    for (int j = 0; j < nv; ++j) {
      if ((point(0, j) - point(nu - 1, j)).norm() > limit) {
        return false;
      }
    }
  } else {
    for (int i = 0; i < nu; ++i) {
      if ((point(i, 0) - point(i, nv - 1)).norm() > limit) {
        return false;
      }
    }
  }
  return true;
}

// T(v,u) = S(u,v): control net transposed, knot vectors exchanged.
NurbsSurface NurbsSurface::transposed() const {
  const int nu = count_u();
  const int nv = count_v();
  std::vector<Eigen::Vector3d> pts(points_.size());
  std::vector<double> w(weights_.size());
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      pts[static_cast<std::size_t>(j + nv * i)] = point(i, j);
      w[static_cast<std::size_t>(j + nv * i)] = weight(i, j);
    }
  }
  return NurbsSurface(v_, u_, std::move(pts), std::move(w));
}

// Knots u'_k = a + b - u_{m-k}, control points i -> n_u - 1 - i.
NurbsSurface NurbsSurface::reversed_u() const {
  const std::vector<double>& u = u_.knots();
  const double a = u_.domain_begin();
  const double b = u_.domain_end();
  std::vector<double> reversed(u.size());
  for (std::size_t k = 0; k < u.size(); ++k)
    reversed[k] = a + b - u[u.size() - 1 - k];
  const int nu = count_u();
  const int nv = count_v();
  std::vector<Eigen::Vector3d> pts(points_.size());
  std::vector<double> w(weights_.size());
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      pts[static_cast<std::size_t>(i + nu * j)] = point(nu - 1 - i, j);
      w[static_cast<std::size_t>(i + nu * j)] = weight(nu - 1 - i, j);
    }
  }
  return NurbsSurface(KnotVector(std::move(reversed), u_.degree()), v_, std::move(pts),
                      std::move(w));
}

}  // namespace isomuscle::geometry
