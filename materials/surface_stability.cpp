#include "materials/surface_stability.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <array>
#include <cmath>
#include <complex>
#include <stdexcept>

#include "materials/strong_ellipticity.hpp"

namespace isomuscle::materials {

namespace {

using Complex = std::complex<double>;
using Vector3c = Eigen::Matrix<Complex, 3, 1>;

// The depth mesh: elements graded geometrically from the surface (first element 0.036 / k) to
// the clamped bottom at 60 / k, where a surface wave of decay rate 0.3 k, slower than any met in
// the tests (Biot's neo-Hookean threshold: 0.30), has fallen to e^-18.
constexpr int kElements = 40;
constexpr double kDepth = 60.0;
constexpr double kGrading = 5.5;

double node_depth(int e) {
  return kDepth * std::expm1(kGrading * e / kElements) / std::expm1(kGrading);
}

// The lowest eigenvalue of the surface energy against the mass for one tangent t (module comment).
class SurfaceEnergy {
 public:
  SurfaceEnergy(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S, const Matrix6d& tangent,
                double pressure, const Eigen::Vector3d& normal)
      : pressure_(pressure), inward_(-normal) {
    // A0_ijkl = J^-1 F_jJ F_lL A_iJkL, row 3 i + j, column 3 k + l.
    const Matrix9d A = first_elasticity(F, S, tangent);
    const double J = F.determinant();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) {
            double a = 0.0;
            for (int JJ = 0; JJ < 3; ++JJ)
              for (int LL = 0; LL < 3; ++LL)
                a += F(j, JJ) * F(l, LL) * A(3 * i + JJ, 3 * k + LL);
            A0_(3 * i + j, 3 * k + l) = a / J;
          }
  }

  double lowest(const Eigen::Vector3d& t) const {
    const int nodes = 2 * kElements + 1;   // quadratic elements
    const int unknowns = 3 * (nodes - 1);  // the bottom node is clamped
    const int pressures = kElements + 1;   // linear pressures at the element ends
    Eigen::MatrixXcd K = Eigen::MatrixXcd::Zero(unknowns, unknowns);
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(unknowns, unknowns);
    Eigen::MatrixXcd C = Eigen::MatrixXcd::Zero(pressures, unknowns);
    const std::array<double, 3> gauss{-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    const std::array<double, 3> weight{5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    const Complex I(0.0, 1.0);
    for (int e = 0; e < kElements; ++e) {
      const double y0 = node_depth(e), h = node_depth(e + 1) - y0;
      for (int g = 0; g < 3; ++g) {
        const double x = 0.5 * (gauss[g] + 1.0), w = 0.5 * weight[g] * h;
        // Quadratic shape functions on [0, 1] (nodes 0, 1/2, 1) and their y-derivatives.
        const std::array<double, 3> N{(1 - x) * (1 - 2 * x), 4 * x * (1 - x), x * (2 * x - 1)};
        const std::array<double, 3> dN{(4 * x - 3) / h, (4 - 8 * x) / h, (4 * x - 1) / h};
        const std::array<double, 2> L{1 - x, x};
        // grad u = sum_a U_a (x) c_a, c_a = i N_a t + N_a' nu (k = 1).
        std::array<Vector3c, 3> c;
        for (int a = 0; a < 3; ++a)
          c[a] = I * N[a] * t.cast<Complex>() + dN[a] * inward_.cast<Complex>();
        for (int a = 0; a < 3; ++a) {
          const int row = 3 * (2 * e + a);
          if (row >= unknowns)
            continue;
          for (int b = 0; b < 3; ++b) {
            const int col = 3 * (2 * e + b);
            if (col >= unknowns)
              continue;
            for (int r = 0; r < 3; ++r)
              for (int s = 0; s < 3; ++s) {
                Complex k = 0.0;
                for (int j = 0; j < 3; ++j)
                  for (int l = 0; l < 3; ++l)
                    k += std::conj(c[a][j]) * A0_(3 * r + j, 3 * s + l) * c[b][l];
                k += pressure_ * (std::conj(c[a][r]) * c[b][s] - std::conj(c[a][s]) * c[b][r]);
                K(row + r, col + s) += w * k;
              }
            for (int r = 0; r < 3; ++r)
              M(row + r, col + r) += w * N[a] * N[b];
          }
          for (int p = 0; p < 2; ++p)
            for (int s = 0; s < 3; ++s)
              C(e + p, row + s) += w * L[p] * c[a][s];
        }
      }
    }
    // Displacements with div u = 0 in the weak sense: the null space of C.
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXcd> qr(C.adjoint());
    const Eigen::MatrixXcd Q = qr.householderQ();
    const Eigen::MatrixXcd Z = Q.rightCols(unknowns - qr.rank());
    Eigen::MatrixXcd Kz = Z.adjoint() * K * Z;
    Kz = (0.5 * (Kz + Kz.adjoint())).eval();
    Eigen::MatrixXcd Mz = Z.adjoint() * M.cast<Complex>() * Z;
    Mz = (0.5 * (Mz + Mz.adjoint())).eval();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> eig(Kz, Mz,
                                                                         Eigen::EigenvaluesOnly);
    return eig.eigenvalues()[0];
  }

 private:
  Matrix9d A0_;
  double pressure_;
  Eigen::Vector3d inward_;
};

}  // namespace

SurfaceStabilityResult surface_stability(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S,
                                         const Matrix6d& tangent, double pressure,
                                         const Eigen::Vector3d& normal, int directions) {
  if (!(F.determinant() > 0.0))
    throw std::invalid_argument("surface_stability: det F <= 0");
  if (!(std::abs(normal.norm() - 1.0) < 1e-9))
    throw std::invalid_argument("surface_stability: the normal must be a unit vector");
  if (directions < 4)
    throw std::invalid_argument("surface_stability: directions must be at least 4");
  const SurfaceEnergy energy(F, S, tangent, pressure, normal);
  const Eigen::Vector3d e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
  const auto tangent_at = [&](double theta) {
    return Eigen::Vector3d(std::cos(theta) * e1 + std::sin(theta) * e2);
  };
  // t and -t give the same energy: half a turn, then golden section about the best.
  const double step = M_PI / directions;
  double best_theta = 0.0, best = INFINITY;
  for (int d = 0; d < directions; ++d) {
    const double value = energy.lowest(tangent_at(d * step));
    if (value < best) {
      best = value;
      best_theta = d * step;
    }
  }
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = best_theta - step, b = best_theta + step;
  double x1 = b - golden * (b - a), x2 = a + golden * (b - a);
  double f1 = energy.lowest(tangent_at(x1)), f2 = energy.lowest(tangent_at(x2));
  for (int it = 0; it < 24; ++it) {
    if (f1 < f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - golden * (b - a);
      f1 = energy.lowest(tangent_at(x1));
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + golden * (b - a);
      f2 = energy.lowest(tangent_at(x2));
    }
  }
  for (const auto& [theta, value] : {std::pair{x1, f1}, std::pair{x2, f2}}) {
    if (value < best) {
      best = value;
      best_theta = theta;
    }
  }
  return {best, tangent_at(best_theta)};
}

}  // namespace isomuscle::materials
