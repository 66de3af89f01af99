// continuum element kernels on one trilinear hexahedron (8 nodes, 2 x 2 x 2 Gauss points, edge
// h): the tangents against central differences of the internal force, symmetry, rigid rotations,
// the mean dilatation projection, and the linearised local update of the mixed formulation.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <vector>

#include "continuum/element_kernels.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::continuum {
namespace {

constexpr double kEdge = 0.01;  // m

// Tabulated reference data of the cube [0, h]^3 with trilinear functions, pressure functions
// 1 (m = 1) or 1, x, y, z in reference coordinates (m = 4), and M_e = int N N^T dV.
struct HexElement {
  int m = 1;
  std::vector<Eigen::Vector3d> gradients;  // 8 points x 8 nodes
  std::vector<double> dv;
  std::vector<double> pressure;  // 8 points x m
  std::vector<Eigen::Vector3d> fibres;
  Eigen::MatrixXd M;
  Eigen::LLT<Eigen::MatrixXd> mass;

  explicit HexElement(int pressure_size) : m(pressure_size) {
    const double g = 0.5 / std::sqrt(3.0);
    const double points[2] = {0.5 - g, 0.5 + g};
    M = Eigen::MatrixXd::Zero(m, m);
    for (int k = 0; k < 2; ++k) {
      for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
          const Eigen::Vector3d xi(points[i], points[j], points[k]);
          for (int c = 0; c < 8; ++c) {
            const int a[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
            Eigen::Vector3d grad;
            for (int d = 0; d < 3; ++d) {
              double v = 1.0;
              for (int e = 0; e < 3; ++e) {
                const double f = a[e] == 1 ? xi[e] : 1.0 - xi[e];
                const double df = a[e] == 1 ? 1.0 : -1.0;
                v *= e == d ? df : f;
              }
              grad[d] = v / kEdge;
            }
            gradients.push_back(grad);
          }
          dv.push_back(0.125 * kEdge * kEdge * kEdge);
          Eigen::VectorXd N(m);
          N[0] = 1.0;
          for (int d = 1; d < m; ++d) {
            N[d] = 2.0 * xi[d - 1] - 1.0;
          }
          pressure.insert(pressure.end(), N.data(), N.data() + m);
          M.noalias() += dv.back() * N * N.transpose();
          fibres.push_back(Eigen::Vector3d(1.0, 1.0, 0.0).normalized());
        }
      }
    }
    mass.compute(M);
  }

  ElementView view() const {
    ElementView v;
    v.nen = 8;
    v.nqp = 8;
    v.gradients = gradients.data();
    v.dv = dv.data();
    v.pressure_size = m;
    v.pressure = pressure.data();
    return v;
  }
};

// Node positions of the cube, column c = corner c.
Eigen::Matrix<double, 3, 8> corners() {
  Eigen::Matrix<double, 3, 8> X;
  for (int c = 0; c < 8; ++c) {
    X.col(c) = kEdge * Eigen::Vector3d(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  }
  return X;
}

// A fixed non-symmetric deformation of the cube: about 10 % strains.
Eigen::Matrix<double, 3, 8> deformation() {
  Eigen::Matrix<double, 3, 8> u;
  for (int c = 0; c < 8; ++c) {
    for (int i = 0; i < 3; ++i) {
      u(i, c) = 0.1 * kEdge * std::sin(1.0 + 3.0 * c + 1.7 * i);
    }
  }
  return u;
}

struct Evaluation {
  Eigen::VectorXd fe;
  Eigen::MatrixXd ke;
};

class Kernels : public ::testing::Test {
 protected:
  std::unique_ptr<materials::MaterialLaw> law =
      materials::make_material("neo_hookean", {{"C10", 1e4}, {"K", 1e6}});

  MaterialContext context(const HexElement& el) const {
    MaterialContext ctx;
    ctx.law = law.get();
    ctx.fibres = el.fibres.data();
    return ctx;
  }

  // Displacement (mixed == false) or mixed kernel with exact projections at u.
  Evaluation run(const HexElement& el, bool mixed, const Eigen::Matrix<double, 3, 8>& u,
                 bool tangent, ElementWorkspace& ws) const {
    ws.ue = u;
    const KernelStatus s =
        mixed ? mixed_kernel(el.view(), context(el), el.mass, el.M, nullptr, tangent, ws)
              : displacement_kernel(el.view(), context(el), tangent, ws);
    EXPECT_TRUE(s.ok());
    return {ws.fe, ws.ke};
  }

  // max |K - K_fd| / max |K| with central differences of f_e, step 1e-7 h.
  double tangent_error(const HexElement& el, bool mixed) const {
    ElementWorkspace ws(8, 8, el.m);
    const Eigen::Matrix<double, 3, 8> u = deformation();
    const Evaluation at = run(el, mixed, u, true, ws);
    EXPECT_LT((at.ke - at.ke.transpose()).cwiseAbs().maxCoeff(),
              1e-12 * at.ke.cwiseAbs().maxCoeff());
    const double step = 1e-7 * kEdge;
    double error = 0.0;
    for (int j = 0; j < 24; ++j) {
      Eigen::Matrix<double, 3, 8> up = u;
      Eigen::Matrix<double, 3, 8> um = u;
      up(j % 3, j / 3) += step;
      um(j % 3, j / 3) -= step;
      const Eigen::VectorXd fp = run(el, mixed, up, false, ws).fe;
      const Eigen::VectorXd fm = run(el, mixed, um, false, ws).fe;
      const Eigen::VectorXd column = (fp - fm) / (2.0 * step);
      error = std::max(error, (column - at.ke.col(j)).cwiseAbs().maxCoeff());
    }
    return error / at.ke.cwiseAbs().maxCoeff();
  }
};

TEST_F(Kernels, TangentsMatchCentralDifferences) {
  const double displacement = tangent_error(HexElement(1), false);
  const double mean_dilatation = tangent_error(HexElement(1), true);
  const double linear = tangent_error(HexElement(4), true);
  std::printf("max |K - K_fd| / max |K|: displacement %.2e, mixed m = 1 %.2e, m = 4 %.2e\n",
              displacement, mean_dilatation, linear);
  EXPECT_LT(displacement, 1e-7);
  EXPECT_LT(mean_dilatation, 1e-7);
  EXPECT_LT(linear, 1e-7);
}

// A rigid rotation gives F = R, S = 0 and no internal force (objectivity).
TEST_F(Kernels, RigidRotationIsStressFree) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 2).normalized()).matrix();
  const Eigen::Matrix<double, 3, 8> X = corners();
  const Eigen::Matrix<double, 3, 8> u = R * X - X;
  for (bool mixed : {false, true}) {
    const HexElement el(1);
    ElementWorkspace ws(8, 8, 1);
    const Evaluation ev = run(el, mixed, u, false, ws);
    const double scale = law->shear_modulus() * kEdge * kEdge;  // N
    EXPECT_LT(ev.fe.cwiseAbs().maxCoeff(), 1e-12 * scale) << mixed;
    EXPECT_LT((ws.F[3] - R).norm(), 1e-14);
  }
}

// m = 1 is the mean dilatation method: J~ = v_e / V_e, p~ = U'(J~) at every point.
TEST_F(Kernels, MeanDilatationProjection) {
  const HexElement el(1);
  ElementWorkspace ws(8, 8, 1);
  run(el, true, deformation(), false, ws);
  double v = 0.0;
  double V = 0.0;
  for (int q = 0; q < 8; ++q) {
    v += ws.J[q] * el.dv[q];
    V += el.dv[q];
  }
  for (int q = 0; q < 8; ++q) {
    EXPECT_NEAR(ws.J_bar[q], v / V, 1e-15);
    EXPECT_NEAR(ws.p_bar[q], law->volumetric(v / V)[1], 1e-9 * law->bulk_modulus());
  }
}

// With a base at u0 the kernel updates theta, pi by the linearised local equations: at u0 itself
// it reproduces the exact projection, at u0 + du it differs from it by O(|du|^2) (header).
TEST_F(Kernels, LinearisedLocalUpdateFromBase) {
  const HexElement el(4);
  const int m = el.m;
  ElementWorkspace ws(8, 8, m);
  const Eigen::Matrix<double, 3, 8> u0 = deformation();
  run(el, true, u0, true, ws);
  // Keep the base (the workspace is overwritten by the next evaluations).
  const Eigen::Matrix<double, 3, 8> ue = ws.ue;
  const Eigen::VectorXd theta = ws.theta, pi = ws.pi, R_pi = ws.R_pi, R_theta = ws.R_theta;
  const Eigen::MatrixXd G = ws.G, K_JJ = ws.K_JJ;
  const Eigen::VectorXd f0 = ws.fe;
  MixedBase base;
  base.ue = ue.data();
  base.theta = theta.data();
  base.pi = pi.data();
  base.R_pi = R_pi.data();
  base.R_theta = R_theta.data();
  base.G = G.data();
  base.K_JJ = K_JJ.data();
  auto theta_difference = [&](double scale) {
    Eigen::Matrix<double, 3, 8> u = u0;
    for (int c = 0; c < 8; ++c) {
      u.col(c) +=
          scale * kEdge * Eigen::Vector3d(std::cos(c), std::sin(2.0 * c), std::cos(3.0 * c));
    }
    ws.ue = u;
    EXPECT_TRUE(mixed_kernel(el.view(), context(el), el.mass, el.M, &base, false, ws).ok());
    const Eigen::VectorXd linearised = ws.theta;
    run(el, true, u, false, ws);
    return (linearised - ws.theta).cwiseAbs().maxCoeff();
  };
  ws.ue = u0;
  ASSERT_TRUE(mixed_kernel(el.view(), context(el), el.mass, el.M, &base, false, ws).ok());
  EXPECT_LT((ws.fe - f0).cwiseAbs().maxCoeff(), 1e-12 * f0.cwiseAbs().maxCoeff());
  const double d1 = theta_difference(1e-2);
  const double d2 = theta_difference(5e-3);
  std::printf("linearised J~ update error: %.3e (du = 1e-2 h), %.3e (du = 5e-3 h), ratio %.2f\n",
              d1, d2, d1 / d2);
  EXPECT_GT(d1, 0.0);
  EXPECT_NEAR(d1 / d2, 4.0, 0.2);  // second order
}

// An inverted configuration is reported with the point and J, not as NaN.
TEST_F(Kernels, InvertedElementIsReported) {
  const HexElement el(1);
  ElementWorkspace ws(8, 8, 1);
  Eigen::Matrix<double, 3, 8> u = Eigen::Matrix<double, 3, 8>::Zero();
  u.row(2) = -2.0 * corners().row(2);  // z -> -z: det F = -1
  ws.ue = u;
  const KernelStatus s = displacement_kernel(el.view(), context(el), true, ws);
  EXPECT_EQ(s.kind, KernelStatus::Kind::inverted);
  EXPECT_EQ(s.point, 0);
  EXPECT_NEAR(s.value, -1.0, 1e-14);
  EXPECT_NE(describe_kernel_status(s, law->name()).find("<= 0 (inverted)"), std::string::npos);
}

}  // namespace
}  // namespace isomuscle::continuum
