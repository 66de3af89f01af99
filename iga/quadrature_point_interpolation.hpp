#pragma once
// Values between the quadrature points of one element. The converged stress of a rate- or
// history-dependent law exists only at the quadrature points, where its internal variables live:
// evaluating the law at F(xi) of another point with a quadrature point's history makes the change
// of fibre stretch between the two points look like a stretch rate of |F(xi) N| - |F_q N| over dt,
// a spurious contraction velocity of the Hill element (thesis 3.39) that grows as dt shrinks.
// Instead the converged values are interpolated: the tensor-product Lagrange polynomial through
// the element's Gauss points (the Gauss-point extrapolation of commercial FE codes), exact at the
// points, degree n_d - 1 in direction d, so exact for the element's pressure space and for any
// field of that degree.
#include <Eigen/Core>
#include <vector>

#include "iga/space.hpp"

namespace isomuscle::iga {

// Weights w_q (one per quadrature point of element e, in the space's point order) with
// value(xi) = sum_q w_q value_q; they sum to 1. xi is a parametric point of element e (its closed
// box); throws std::invalid_argument otherwise.
std::vector<double> quadrature_point_weights(const Space& space, int e, const Eigen::Vector3d& xi);

}  // namespace isomuscle::iga
