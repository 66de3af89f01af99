#pragma once
// Strong ellipticity of a law's incremental response at one material point: whether plane waves
// of every direction propagate, i.e. whether the incremental boundary-value problem can form a
// displacement discontinuity (a shear band, a fold) that no mesh resolves. For the first
// elasticity tensor A = dP/dF (P = F S) and a reference wave normal N the acoustic tensor is
//
//   Q_ik(N) = A_iJkL N_J N_L = δ_ik (N · S N) + F_iI F_kK C_IJKL N_J N_L,   C = dS/dE,
//
// (Marsden & Hughes 1983, §4.4; Holzapfel 2000, §6.7). A nearly incompressible muscle is tested on
// isochoric waves only: amplitudes a ⊥ m, m = F^-T N / |F^-T N| the deformed normal. The
// pressure's term p J F^-T contributes nothing to Q(N) for those (its derivative contracts to
// m ⊗ m - m ⊗ m), so the law's isochoric part alone decides. The measure is
//
//   e = min over N, and over unit a ⊥ m(N), of a · Q(N) a      (Pa; > 0: strongly elliptic)
//
// searched on a Fibonacci set of normals over the half sphere (Q(-N) = Q(N)). At F = I with an
// isotropic law e is the shear modulus. The refined search starts from a coarse set and walks
// downhill from its best normals (a pattern search on the sphere), which finds the minimum to
// round-off at a tenth of the cost of a fine set: what a scan of every quadrature point of a
// body needs (continuum/point_ellipticity.hpp).
#include <Eigen/Core>

#include "materials/material_law.hpp"

namespace isomuscle::materials {

struct EllipticityResult {
  double smallest = 0.0;                              // e, Pa
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // the reference N that gave it
};

// The first elasticity tensor A_iJkL = dP_iJ/dF_kL = δ_ik S_JL + F_iI F_kK C_IJKL as a 9 x 9 matrix
// over the pairs (i, J) and (k, L), row 3 i + J, column 3 k + L, so that Q(N)_ik = A_(iJ)(kL) N_J
// N_L: built once per point, it makes a wave normal cost 81 products.
using Matrix9d = Eigen::Matrix<double, 9, 9>;
Matrix9d first_elasticity(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                          const Matrix6d& tangent);

// Q(N) of the formula above; tangent in the Voigt convention of material_law.hpp.
Eigen::Matrix3d acoustic_tensor(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                const Matrix6d& tangent, const Eigen::Vector3d& N);

// e over `normals` reference normals (at least 1; 2000 resolve a minimum to about 0.1 % of its
// curvature scale). Throws std::invalid_argument when normals < 1 or det F <= 0.
EllipticityResult isochoric_ellipticity(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                        const Matrix6d& tangent, int normals = 2000);

// e from `normals` Fibonacci normals (at least 8), then a pattern search on the sphere from the
// best few of them: steps of the coarse spacing along two tangent directions, halved when no step
// descends, down to 1e-8 rad. Same exceptions.
EllipticityResult refined_isochoric_ellipticity(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                                const Matrix6d& tangent, int normals = 96);

}  // namespace isomuscle::materials
