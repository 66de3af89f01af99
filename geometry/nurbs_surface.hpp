#pragma once
// Non-uniform rational B-spline surface (thesis 5.11):
//   S(u,v) = sum_ij N_i(u) N_j(v) w_ij P_ij / sum_ij N_i(u) N_j(v) w_ij.
// Control points are stored Cartesian with separate weights; index i + n_u * j.
#include <Eigen/Core>
#include <vector>

#include "geometry/knot_vector.hpp"

namespace isomuscle::geometry {

class NurbsSurface {
 public:
  NurbsSurface() = default;
  // Throws std::invalid_argument when the counts do not match the knot vectors, or a weight is not
  // finite and positive, or a point is not finite.
  NurbsSurface(KnotVector u, KnotVector v, std::vector<Eigen::Vector3d> points,
               std::vector<double> weights);

  const KnotVector& knots_u() const { return u_; }
  const KnotVector& knots_v() const { return v_; }
  int count_u() const { return u_.num_basis(); }
  int count_v() const { return v_.num_basis(); }
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  const std::vector<double>& weights() const { return weights_; }
  const Eigen::Vector3d& point(int i, int j) const { return points_[i + count_u() * j]; }
  double weight(int i, int j) const { return weights_[i + count_u() * j]; }
  bool is_rational() const;  // any weight differs from the first

  Eigen::Vector3d evaluate(double u, double v) const;
  // Point and first partial derivatives: columns of d are dS/du, dS/dv.
  void evaluate_derivatives(double u, double v, Eigen::Vector3d& point,
                            Eigen::Matrix<double, 3, 2>& d) const;
  // True when the first and last control rows in direction dir (0 = u, 1 = v) coincide within tol
  // times the bounding-box diagonal (a closed clamped surface).
  bool is_closed(int dir, double tol = 1e-10) const;
  // Same surface with u and v exchanged.
  NurbsSurface transposed() const;
  // Same surface with u reversed: S'(u, v) = S(a + b - u, v) on the same domain [a, b]; the
  // normal dS/du x dS/dv flips.
  NurbsSurface reversed_u() const;

 private:
  KnotVector u_, v_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<double> weights_;
};

}  // namespace isomuscle::geometry
