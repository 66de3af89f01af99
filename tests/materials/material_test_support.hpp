#pragma once
// Shared helpers of the materials tests: random deformation gradients and fibres, central
// differences of a law's stress with respect to the Green–Lagrange strain, error measures.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "materials/material_law.hpp"

namespace isomuscle::materials::testing {

inline Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

inline Eigen::Vector3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector3d v(n(rng), n(rng), n(rng));
  return v.normalized();
}

// F = Q (R diag(stretches) R^T + shear), stretches in [lo, hi], shear entries in [-0.2, 0.2],
// rotations Q, R random; redrawn until det F > 0.
inline Eigen::Matrix3d random_F(std::mt19937& rng, double lo = 0.7, double hi = 1.4) {
  std::uniform_real_distribution<double> st(lo, hi), sh(-0.2, 0.2);
  for (;;) {
    const Eigen::Matrix3d R = random_rotation(rng);
    const Eigen::Vector3d l(st(rng), st(rng), st(rng));
    Eigen::Matrix3d U = R * l.asDiagonal() * R.transpose();
    U(0, 1) += sh(rng);
    U(1, 2) += sh(rng);
    U(2, 0) += sh(rng);
    const Eigen::Matrix3d F = random_rotation(rng) * U;
    if (F.determinant() > 0.2)
      return F;
  }
}

// Symmetric square root of an SPD matrix: a deformation gradient with F^T F = C.
inline Eigen::Matrix3d sqrt_spd(const Eigen::Matrix3d& C) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  return es.eigenvectors() * es.eigenvalues().cwiseSqrt().asDiagonal() *
         es.eigenvectors().transpose();
}

enum class Part { full, isochoric };

struct Evaluation {
  PointStatus status = PointStatus::ok;
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  Matrix6d tangent = Matrix6d::Zero();
  std::vector<double> trial;
};

inline Evaluation evaluate(const MaterialLaw& law, const PointInput& in, Part part = Part::full,
                           bool tangent = true) {
  Evaluation e;
  e.trial.assign(static_cast<std::size_t>(law.history_size()), 0.0);
  PointResult r;
  r.history = e.trial;
  e.status =
      part == Part::full ? law.evaluate(in, r, tangent) : law.evaluate_isochoric(in, r, tangent);
  e.S = r.S;
  e.tangent = r.tangent;
  return e;
}

// Central differences of S (Voigt) with respect to E (engineering shear): column j from
// C +- 2h dE_j, evaluated at F = sqrt(C) (the laws depend on C only, checked by the objectivity
// tests). Returns false when any evaluation fails.
inline bool fd_tangent(const MaterialLaw& law, const PointInput& in, Part part, Matrix6d& out,
                       double h = 1e-6) {
  const Eigen::Matrix3d C = in.F.transpose() * in.F;
  constexpr int I[6] = {0, 1, 2, 0, 1, 0};
  constexpr int J[6] = {0, 1, 2, 1, 2, 2};
  for (int j = 0; j < 6; ++j) {
    Eigen::Matrix3d dC = Eigen::Matrix3d::Zero();
    // dE_voigt = h e_j: dE_ii = h, or dE_ij = dE_ji = h/2 for shears; dC = 2 dE.
    if (I[j] == J[j]) {
      dC(I[j], I[j]) = 2.0 * h;
    } else {
      dC(I[j], J[j]) = h;
      dC(J[j], I[j]) = h;
    }
    PointInput p = in;
    p.F = sqrt_spd(C + dC);
    const Evaluation plus = evaluate(law, p, part, false);
    p.F = sqrt_spd(C - dC);
    const Evaluation minus = evaluate(law, p, part, false);
    if (plus.status != PointStatus::ok || minus.status != PointStatus::ok)
      return false;
    out.col(j) = (to_voigt_stress(plus.S) - to_voigt_stress(minus.S)) / (2.0 * h);
  }
  return true;
}

// max |A - B| / max |B|.
inline double relative_error(const Matrix6d& A, const Matrix6d& B) {
  return (A - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff();
}

}  // namespace isomuscle::materials::testing
