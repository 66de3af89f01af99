#include "materials/kinematics.hpp"

#include <Eigen/LU>
#include <cmath>

namespace isomuscle::materials {

namespace {
// Voigt index pairs in the order 11, 22, 33, 12, 23, 13.
constexpr int kVoigtI[6] = {0, 1, 2, 0, 1, 0};
constexpr int kVoigtJ[6] = {0, 1, 2, 1, 2, 2};
}  // namespace

// C = F^T F, J = det F, Ī1 = J^(-2/3) tr C (thesis 3.19); dimensionless.
bool compute_kinematics(const Eigen::Matrix3d& F, Kinematics& k) {
  if (!F.allFinite())
    return false;
  k.F = F;
  k.J = F.determinant();
  if (!(k.J > 0.0) || !std::isfinite(k.J))
    return false;
  k.C.noalias() = F.transpose() * F;
  k.C_inv = k.C.inverse();
  const double cbrt_J = std::cbrt(k.J);
  k.J_m23 = 1.0 / (cbrt_J * cbrt_J);
  k.I1 = k.C.trace();
  k.I1_bar = k.J_m23 * k.I1;
  return k.C_inv.allFinite();
}

// I4 = N·C·N (thesis 5.30 with λf² = I4); dimensionless.
double fibre_invariant(const Kinematics& k, const Eigen::Vector3d& N) {
  return N.dot(k.C * N);
}

// Symmetric tensor -> Voigt vector (11, 22, 33, 12, 23, 13).
Vector6d voigt(const Eigen::Matrix3d& A) {
  Vector6d v;
  v << A(0, 0), A(1, 1), A(2, 2), A(0, 1), A(1, 2), A(0, 2);
  return v;
}

// (A ⊙ A)_ijkl = 1/2 (A_ik A_jl + A_il A_jk) (thesis 5.48 with A = C^-1, sign taken out).
Matrix6d symmetric_product_voigt(const Eigen::Matrix3d& A) {
  Matrix6d M;
  for (int a = 0; a < 6; ++a) {
    const int i = kVoigtI[a], j = kVoigtJ[a];
    for (int b = a; b < 6; ++b) {
      const int k = kVoigtI[b], l = kVoigtJ[b];
      M(a, b) = 0.5 * (A(i, k) * A(j, l) + A(i, l) * A(j, k));
      M(b, a) = M(a, b);
    }
  }
  return M;
}

// sigma = F S F^T / J (thesis 5.41); Pa.
Eigen::Matrix3d push_forward_stress(const Eigen::Matrix3d& F, double J, const Eigen::Matrix3d& S) {
  Eigen::Matrix3d FS;
  FS.noalias() = F * S;
  Eigen::Matrix3d sigma;
  sigma.noalias() = FS * F.transpose();
  sigma /= J;
  return sigma;
}

}  // namespace isomuscle::materials
