#include "materials/decoupled_hyperelastic.hpp"

namespace isomuscle::materials {

// psi4 = U'_f/(2 λ̄f), psi44 = (U''_f - U'_f/λ̄f)/(4 λ̄f²) from Ī4 = λ̄f² (chain rule); Pa.
void set_fibre_derivatives(double lambda_f_bar, double dUf, double d2Uf, IsochoricDerivatives& d) {
  d.psi4 = dUf / (2.0 * lambda_f_bar);
  d.psi44 = (d2Uf - dUf / lambda_f_bar) / (4.0 * lambda_f_bar * lambda_f_bar);
}

// Thesis 5.40 (stress) and the corrected 5.47 (tangent; the thesis prints + instead of - in
// front of λ̄f^-1 U'_f in the N⊗N⊗N⊗N term, cf. its own 5.49); Pa.
void decoupled_stress(const Kinematics& k, const Eigen::Vector3d& N, double I4_bar,
                      const IsochoricDerivatives& iso, const VolumetricDerivatives* vol,
                      Eigen::Matrix3d& S, Matrix6d* tangent) {
  const bool fibre = iso.psi4 != 0.0 || iso.psi44 != 0.0;
  const double Jm23 = k.J_m23;
  // S = 2 psi1 (J^(-2/3) I - Ī1/3 C^-1) + 2 psi4 (J^(-2/3) A - Ī4/3 C^-1) + J U' C^-1, A = N⊗N.
  double cinv_coeff = -2.0 / 3.0 * (iso.psi1 * k.I1_bar + iso.psi4 * I4_bar);
  if (vol != nullptr)
    cinv_coeff += k.J * vol->dU;
  S = cinv_coeff * k.C_inv;
  S.diagonal().array() += 2.0 * iso.psi1 * Jm23;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  if (fibre) {
    A.noalias() = N * N.transpose();
    S.noalias() += (2.0 * iso.psi4 * Jm23) * A;
  }
  if (tangent == nullptr)
    return;

  const Vector6d c = voigt(k.C_inv);
  Vector6d i6;
  i6 << 1.0, 1.0, 1.0, 0.0, 0.0, 0.0;
  Matrix6d& T = *tangent;
  const Vector6d d1 = Jm23 * i6 - (k.I1_bar / 3.0) * c;  // dĪ1/dC
  T.noalias() = (4.0 * iso.psi11) * d1 * d1.transpose();
  Vector6d g = (4.0 * iso.psi1) * i6;
  double q = 4.0 * iso.psi1 * k.I1_bar;
  if (fibre) {
    const Vector6d a = voigt(A);
    const Vector6d d4 = Jm23 * a - (I4_bar / 3.0) * c;  // dĪ4/dC
    T.noalias() += (4.0 * iso.psi44) * d4 * d4.transpose();
    g.noalias() += (4.0 * iso.psi4) * a;
    q += 4.0 * iso.psi4 * I4_bar;
  }
  T.noalias() -= (Jm23 / 3.0) * (g * c.transpose() + c * g.transpose());
  double cc_coeff = q / 9.0;
  double sym_coeff = q / 3.0;
  if (vol != nullptr) {
    cc_coeff += k.J * (vol->dU + k.J * vol->d2U);
    sym_coeff -= 2.0 * k.J * vol->dU;
  }
  T.noalias() += cc_coeff * c * c.transpose();
  T.noalias() += sym_coeff * symmetric_product_voigt(k.C_inv);
}

}  // namespace isomuscle::materials
