#pragma once
// Kinematics of one material point: C, J, C^-1, the isochoric invariants (thesis 2.x, 3.18–3.21:
// Ī1 = J^(-2/3) tr C, Ī4 = J^(-2/3) N·C·N), Voigt forms of the fourth-order tensors that every
// hyperelastic tangent needs, and the push-forward S -> Cauchy (thesis 5.41). Dimensionless except
// where a stress is named (Pa).
#include <Eigen/Core>

#include "materials/material_law.hpp"

namespace isomuscle::materials {

struct Kinematics {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d C = Eigen::Matrix3d::Identity();      // right Cauchy–Green F^T F
  Eigen::Matrix3d C_inv = Eigen::Matrix3d::Identity();  // C^-1
  double J = 1.0;                                       // det F
  double J_m23 = 1.0;                                   // J^(-2/3)
  double I1 = 3.0;                                      // tr C
  double I1_bar = 3.0;                                  // J^(-2/3) tr C
};

// Fills k from F. Returns false when F is not finite or J <= 0 (the laws are undefined there).
bool compute_kinematics(const Eigen::Matrix3d& F, Kinematics& k);

// I4 = N·C·N (fibre invariant, thesis 5.30); N need not be the deformed direction.
double fibre_invariant(const Kinematics& k, const Eigen::Vector3d& N);

// Voigt (11, 22, 33, 12, 23, 13) components of a symmetric tensor, no factor 2 on shears.
Vector6d voigt(const Eigen::Matrix3d& A);

// Voigt 6x6 of the fourth-order tensor (A ⊙ A)_ijkl = 1/2 (A_ik A_jl + A_il A_jk) for symmetric A;
// with A = C^-1 it is -dC^-1/dC (thesis 5.48).
Matrix6d symmetric_product_voigt(const Eigen::Matrix3d& A);

// Cauchy stress sigma = F S F^T / J, Pa (push-forward, thesis 5.41).
Eigen::Matrix3d push_forward_stress(const Eigen::Matrix3d& F, double J, const Eigen::Matrix3d& S);

}  // namespace isomuscle::materials
