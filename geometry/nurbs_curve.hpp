#pragma once
// Non-uniform rational B-spline curve C(u) = sum_i N_i(u) w_i P_i / sum_i N_i(u) w_i (thesis 5.6).
// Control points are stored Cartesian with separate weights, as for surfaces and volumes.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "geometry/knot_vector.hpp"

namespace isomuscle::geometry {

class NurbsCurve {
 public:
  NurbsCurve() = default;
  // Throws std::invalid_argument when the number of points or weights differs from
  // knots.num_basis(), or a weight is not finite and positive, or a point is not finite.
  NurbsCurve(KnotVector knots, std::vector<Eigen::Vector3d> points, std::vector<double> weights);

  const KnotVector& knots() const { return knots_; }
  int degree() const { return knots_.degree(); }
  int count() const { return knots_.num_basis(); }
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  const std::vector<double>& weights() const { return weights_; }
  const Eigen::Vector3d& point(int i) const { return points_[i]; }
  double weight(int i) const { return weights_[i]; }
  bool is_rational() const;  // any weight differs from the first
  std::array<double, 2> domain() const { return {knots_.domain_begin(), knots_.domain_end()}; }

  Eigen::Vector3d evaluate(double u) const;
  // First derivative dC/du.
  Eigen::Vector3d derivative(double u) const;
  // Derivatives d^k C/du^k for k = 0..n (NURBS Book A4.2): out[k].
  std::vector<Eigen::Vector3d> derivatives(double u, int n) const;

 private:
  KnotVector knots_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<double> weights_;
};

}  // namespace isomuscle::geometry
