#pragma once
// The element-local space of the mixed near-incompressible formulation: the pressure p~ and the
// dilatation J~ are discontinuous between knot spans and, on each span, tensor polynomials of
// degree k in the element's parametric coordinates t in [-1, 1]^3 (Simo, Taylor & Pister 1985
// three-field u–p–J; deal.II step-44; Elguedj et al. 2008 for NURBS):
//
//   N_m(t) = P_i(t_u) P_j(t_v) P_l(t_w),  0 <= i, j, l <= k,  m = i + (k+1)(j + (k+1) l)
//
// with P_i the Legendre polynomials (well conditioned element mass matrices). k = 0 is the mean
// dilatation method (one constant per element). The element mass matrix M_e = int_e N N^T dV is
// factorised once per element (Cholesky).
//
// Constraint count: a C^(p-1) NURBS space has about 3 n_el displacement DOFs whatever p, so
// k = 0 (n_el constraints, ratio 1/3, as Q1/P0) is the balanced choice for smooth splines; k >= 1
// adds (k+1)^3 constraints per element and over-constrains smooth NURBS (it locks; measured in
// tests/iga). It is offered for comparison and for C^0 (repeated-knot) spaces.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

#include "iga/space.hpp"

namespace isomuscle::iga {

class PressureSpace {
 public:
  PressureSpace() = default;
  // Throws std::invalid_argument when degree is not in 0..4 or a mass matrix is not positive
  // definite (naming the element).
  PressureSpace(const Space& space, int degree);

  int degree() const { return degree_; }
  // Functions per element, (k+1)^3.
  int size() const { return m_; }
  // N_m at quadrature point q (the same for every element: the tensor rule is affine per span).
  const double* values(int q) const { return table_.data() + static_cast<std::size_t>(q) * m_; }
  // Values at a point given in the element's reference coordinates t in [-1, 1]^3.
  void evaluate(const Eigen::Vector3d& t, double* out) const;
  // Cholesky factor of M_e, and M_e itself.
  const Eigen::LLT<Eigen::MatrixXd>& mass(int e) const { return mass_[e]; }
  const Eigen::MatrixXd& mass_matrix(int e) const { return mass_matrix_[e]; }

 private:
  int degree_ = 0;
  int m_ = 1;
  std::vector<double> table_;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> mass_;
  std::vector<Eigen::MatrixXd> mass_matrix_;
};

// Reference coordinates t in [-1, 1]^3 of a parametric point xi in an element's box.
Eigen::Vector3d element_reference_coordinates(const Element& element, const Eigen::Vector3d& xi);

}  // namespace isomuscle::iga
