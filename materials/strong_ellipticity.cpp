#include "materials/strong_ellipticity.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace isomuscle::materials {

namespace {

// Voigt index of the symmetric pair (I, J) in the order 11, 22, 33, 12, 23, 13.
int voigt_index(int i, int j) {
  if (i == j)
    return i;
  return i + j == 1 ? 3 : (i + j == 3 ? 4 : 5);
}

}  // namespace

Eigen::Matrix3d acoustic_tensor(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                const Matrix6d& tangent, const Eigen::Vector3d& N) {
  // B_IK = C_IJKL N_J N_L, then Q = (N · S N) I + F B F^T.
  Eigen::Matrix3d B = Eigen::Matrix3d::Zero();
  for (int I = 0; I < 3; ++I) {
    for (int K = 0; K < 3; ++K) {
      for (int J = 0; J < 3; ++J) {
        for (int L = 0; L < 3; ++L)
          B(I, K) += tangent(voigt_index(I, J), voigt_index(K, L)) * N[J] * N[L];
      }
    }
  }
  return N.dot(S * N) * Eigen::Matrix3d::Identity() + F * B * F.transpose();
}

EllipticityResult isochoric_ellipticity(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                        const Matrix6d& tangent, int normals) {
  if (normals < 1)
    throw std::invalid_argument("isochoric_ellipticity: normals must be at least 1");
  if (!(F.determinant() > 0.0))
    throw std::invalid_argument("isochoric_ellipticity: det F <= 0");
  const Eigen::Matrix3d F_inv_T = F.inverse().transpose();
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  EllipticityResult best;
  best.smallest = std::numeric_limits<double>::infinity();
  for (int s = 0; s < normals; ++s) {
    const double z = 1.0 - (s + 0.5) / normals;  // the half sphere z > 0
    const double r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d N(r * std::cos(s * golden_angle), r * std::sin(s * golden_angle), z);
    const Eigen::Matrix3d Q = acoustic_tensor(F, S, tangent, N);
    const Eigen::Vector3d m = (F_inv_T * N).normalized();
    const Eigen::Vector3d t1 = m.unitOrthogonal(), t2 = m.cross(t1);
    Eigen::Matrix2d q;
    q(0, 0) = t1.dot(Q * t1);
    q(1, 1) = t2.dot(Q * t2);
    q(0, 1) = q(1, 0) = 0.5 * (t1.dot(Q * t2) + t2.dot(Q * t1));
    const double e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(q).eigenvalues()[0];
    if (e < best.smallest) {
      best.smallest = e;
      best.normal = N;
    }
  }
  return best;
}

}  // namespace isomuscle::materials
