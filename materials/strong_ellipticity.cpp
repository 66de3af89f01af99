#include "materials/strong_ellipticity.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace isomuscle::materials {

namespace {

// Voigt index of the symmetric pair (I, J) in the order 11, 22, 33, 12, 23, 13.
int voigt_index(int i, int j) {
  if (i == j)
    return i;
  return i + j == 1 ? 3 : (i + j == 3 ? 4 : 5);
}

Eigen::Matrix3d contract(const Matrix9d& A, const Eigen::Vector3d& N) {
  Eigen::Matrix3d Q;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      double q = 0.0;
      for (int J = 0; J < 3; ++J)
        for (int L = 0; L < 3; ++L)
          q += A(3 * i + J, 3 * k + L) * N[J] * N[L];
      Q(i, k) = q;
    }
  return Q;
}

// a · Q(N) a minimised over unit a ⊥ m(N): the smaller eigenvalue of Q on the plane ⊥ m.
class IsochoricWaveStiffness {
 public:
  IsochoricWaveStiffness(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                         const Matrix6d& tangent)
      : A_(first_elasticity(F, S, tangent)), F_inv_T_(F.inverse().transpose()) {}

  double operator()(const Eigen::Vector3d& N) const {
    const Eigen::Matrix3d Q = contract(A_, N);
    const Eigen::Vector3d m = (F_inv_T_ * N).normalized();
    const Eigen::Vector3d t1 = m.unitOrthogonal(), t2 = m.cross(t1);
    const double a = t1.dot(Q * t1), b = t2.dot(Q * t2);
    const double c = 0.5 * (t1.dot(Q * t2) + t2.dot(Q * t1));
    return 0.5 * (a + b) - std::hypot(0.5 * (a - b), c);
  }

 private:
  Matrix9d A_;
  Eigen::Matrix3d F_inv_T_;
};

// Normal s of a Fibonacci set of `normals` over the half sphere z > 0.
Eigen::Vector3d fibonacci_normal(int s, int normals) {
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (s + 0.5) / normals;
  const double r = std::sqrt(1.0 - z * z);
  return {r * std::cos(s * golden_angle), r * std::sin(s * golden_angle), z};
}

void check_input(const Eigen::Matrix3d& F, int normals, int least, const char* who) {
  if (normals < least) {
    throw std::invalid_argument(std::string(who) + ": normals must be at least " +
                                std::to_string(least));
  }
  if (!(F.determinant() > 0.0))
    throw std::invalid_argument(std::string(who) + ": det F <= 0");
}

}  // namespace

Matrix9d first_elasticity(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                          const Matrix6d& tangent) {
  double FC[3][3][3][3] = {};  // F_iI C_IJKL
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int K = 0; K < 3; ++K)
        for (int L = 0; L < 3; ++L)
          for (int I = 0; I < 3; ++I)
            FC[i][J][K][L] += F(i, I) * tangent(voigt_index(I, J), voigt_index(K, L));
  Matrix9d A;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          double a = i == k ? S(J, L) : 0.0;
          for (int K = 0; K < 3; ++K)
            a += F(k, K) * FC[i][J][K][L];
          A(3 * i + J, 3 * k + L) = a;
        }
  return A;
}

Eigen::Matrix3d acoustic_tensor(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                const Matrix6d& tangent, const Eigen::Vector3d& N) {
  return contract(first_elasticity(F, S, tangent), N);
}

EllipticityResult isochoric_ellipticity(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                        const Matrix6d& tangent, int normals) {
  check_input(F, normals, 1, "isochoric_ellipticity");
  const IsochoricWaveStiffness stiffness(F, S, tangent);
  EllipticityResult best;
  best.smallest = std::numeric_limits<double>::infinity();
  for (int s = 0; s < normals; ++s) {
    const Eigen::Vector3d N = fibonacci_normal(s, normals);
    const double e = stiffness(N);
    if (e < best.smallest) {
      best.smallest = e;
      best.normal = N;
    }
  }
  return best;
}

EllipticityResult refined_isochoric_ellipticity(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                                const Matrix6d& tangent, int normals) {
  check_input(F, normals, 8, "refined_isochoric_ellipticity");
  const IsochoricWaveStiffness stiffness(F, S, tangent);
  // The best few coarse normals: a second valley of about the same depth is walked too.
  constexpr int starts = 3;
  std::array<EllipticityResult, starts> best;
  for (EllipticityResult& b : best)
    b.smallest = std::numeric_limits<double>::infinity();
  for (int s = 0; s < normals; ++s) {
    EllipticityResult candidate{stiffness(fibonacci_normal(s, normals)),
                                fibonacci_normal(s, normals)};
    for (EllipticityResult& b : best) {
      if (candidate.smallest < b.smallest)
        std::swap(candidate, b);
    }
  }
  // Each Fibonacci point owns 2 pi / normals of the half sphere's area: the first step.
  const double spacing = std::sqrt(2.0 * M_PI / normals);
  constexpr double finest_step = 1e-8;  // rad
  constexpr int max_evaluations = 500;  // per start; a walk needs about 100
  EllipticityResult result = best[0];
  for (const EllipticityResult& start : best) {
    if (!std::isfinite(start.smallest))
      continue;
    Eigen::Vector3d N = start.normal;
    double e = start.smallest;
    double step = spacing;
    for (int evaluations = 0; step > finest_step && evaluations < max_evaluations;) {
      const Eigen::Vector3d t1 = N.unitOrthogonal(), t2 = N.cross(t1);
      Eigen::Vector3d next = N;
      for (const Eigen::Vector3d& d : {t1, Eigen::Vector3d(-t1), t2, Eigen::Vector3d(-t2)}) {
        const Eigen::Vector3d trial = (N + step * d).normalized();
        const double value = stiffness(trial);
        ++evaluations;
        if (value < e) {
          e = value;
          next = trial;
        }
      }
      if (next == N)
        step *= 0.5;
      N = next;
    }
    if (e < result.smallest)
      result = {e, N};
  }
  return result;
}

}  // namespace isomuscle::materials
