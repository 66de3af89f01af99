#pragma once
// Stress and tangent of a decoupled energy psi = psi_iso(Ī1, Ī4) + U(J) (thesis 3.18, 5.31, 5.40,
// 5.47), written once for every law of this folder. With the derivatives of psi with respect to
// the isochoric invariants given, S = 2 dpsi/dC and the Voigt tangent dS/dE = 4 d²psi/dC² follow
// from the derivatives of Ī1, Ī4 and J with respect to C (Holzapfel 2000, §6.4–6.7).
#include <Eigen/Core>

#include "materials/kinematics.hpp"

namespace isomuscle::materials {

// Derivatives of psi_iso with respect to Ī1 and Ī4 (no mixed term in the laws here), Pa.
struct IsochoricDerivatives {
  double psi1 = 0.0, psi11 = 0.0;  // dpsi/dĪ1, d²psi/dĪ1²
  double psi4 = 0.0, psi44 = 0.0;  // dpsi/dĪ4, d²psi/dĪ4² (zero for isotropic laws)
};

// Derivatives of the volumetric energy U(J), Pa: U'(J) and U''(J).
struct VolumetricDerivatives {
  double dU = 0.0, d2U = 0.0;
};

// For a fibre law written on λ̄f = sqrt(Ī4) with dpsi/dλ̄f = U'_f and d²psi/dλ̄f² = U''_f (thesis
// 5.43, 5.52): psi4 = U'_f / (2 λ̄f), psi44 = (U''_f - U'_f/λ̄f) / (4 λ̄f²).
void set_fibre_derivatives(double lambda_f_bar, double dUf, double d2Uf, IsochoricDerivatives& d);

// S = 2 psi1 dĪ1/dC + 2 psi4 dĪ4/dC [+ J U'(J) C^-1] (thesis 5.40) with
//   dĪ1/dC = J^(-2/3) I - Ī1/3 C^-1,  dĪ4/dC = J^(-2/3) N⊗N - Ī4/3 C^-1,
// and, when tangent != nullptr, its Voigt tangent dS/dE (order 11, 22, 33, 12, 23, 13):
//   4 psi11 d1⊗d1 + 4 psi44 d4⊗d4 - (J^(-2/3)/3)(g⊗C^-1 + C^-1⊗g) + q/9 C^-1⊗C^-1 + q/3 C^-1⊙C^-1
//   [+ J(U' + J U'') C^-1⊗C^-1 - 2 J U' C^-1⊙C^-1]
// with g = 4 psi1 I + 4 psi4 N⊗N and q = 4 psi1 Ī1 + 4 psi4 Ī4. The volumetric part is added only
// when vol != nullptr. N is only read when psi4 or psi44 is nonzero. Overwrites S and *tangent.
void decoupled_stress(const Kinematics& k, const Eigen::Vector3d& N, double I4_bar,
                      const IsochoricDerivatives& iso, const VolumetricDerivatives* vol,
                      Eigen::Matrix3d& S, Matrix6d* tangent);

}  // namespace isomuscle::materials
