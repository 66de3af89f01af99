#pragma once
// Trivariate NURBS solid H(u,v,w) (thesis 5.13): the analysis geometry of the IGA module. Control
// points are stored Cartesian with separate weights; global index i + n_u * (j + n_v * k).
#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

#include "geometry/knot_vector.hpp"

namespace isomuscle::geometry {

// The rational basis functions that are non-zero at one parametric point, with their parametric
// gradients. Reused between calls so that evaluation in quadrature loops does not allocate.
struct VolumeBasis {
  std::vector<int> index;                   // global control point index, (p+1)(q+1)(r+1) entries
  std::vector<double> value;                // R_a
  std::vector<Eigen::Vector3d> derivative;  // (dR_a/du, dR_a/dv, dR_a/dw)
};

class NurbsVolume {
 public:
  NurbsVolume() = default;
  // Throws std::invalid_argument on mismatched counts, non-positive or non-finite weights, or
  // non-finite points.
  NurbsVolume(std::array<KnotVector, 3> knots, std::vector<Eigen::Vector3d> points,
              std::vector<double> weights);

  const KnotVector& knots(int dir) const { return knots_[dir]; }
  const std::array<KnotVector, 3>& all_knots() const { return knots_; }
  int degree(int dir) const { return knots_[dir].degree(); }
  int count(int dir) const { return knots_[dir].num_basis(); }
  int num_control_points() const { return count(0) * count(1) * count(2); }
  int index(int i, int j, int k) const { return i + count(0) * (j + count(1) * k); }
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  const std::vector<double>& weights() const { return weights_; }
  std::vector<Eigen::Vector3d>& mutable_points() { return points_; }

  Eigen::Vector3d evaluate(const Eigen::Vector3d& xi) const;
  // Geometry Jacobian dH/d(u,v,w): column d is the tangent of the isocurve in direction d.
  Eigen::Matrix3d jacobian(const Eigen::Vector3d& xi) const;
  void evaluate_with_jacobian(const Eigen::Vector3d& xi, Eigen::Vector3d& point,
                              Eigen::Matrix3d& jacobian) const;

  // Rational basis and parametric gradients at xi, in the knot span chosen by find_span.
  void evaluate_basis(const Eigen::Vector3d& xi, VolumeBasis& out) const;
  // Same in a given span (spans as returned by KnotVector::find_span), so that a point on an
  // element boundary is evaluated with that element's functions.
  void evaluate_basis_in_span(const std::array<int, 3>& span, const Eigen::Vector3d& xi,
                              VolumeBasis& out) const;

  // Parametric domain per direction.
  std::array<double, 2> domain(int dir) const {
    return {knots_[dir].domain_begin(), knots_[dir].domain_end()};
  }
  // Axis-aligned bounding box of the control points: (min, max).
  std::pair<Eigen::Vector3d, Eigen::Vector3d> bounding_box() const;

 private:
  std::array<KnotVector, 3> knots_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<double> weights_;
};

}  // namespace isomuscle::geometry
