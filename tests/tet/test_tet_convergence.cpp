// Manufactured-solution convergence of small-strain linear elasticity on the unit cube: the
// "linear_elastic" law's tangent at F = I is Hooke's matrix, so one linear solve K u = f at u = 0
// is the linear finite-element solution. L2 errors on structured Kuhn meshes, fitted rates.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>

#include "materials/material_factory.hpp"
#include "tet/tet_elements.hpp"
#include "tet/tet_fibres.hpp"
#include "tet/tet_mesh.hpp"
#include "tet/tet_problem.hpp"
#include "tet/tet_space.hpp"

namespace isomuscle::tet {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kE = 1.0e3;
constexpr double kNu = 0.3;
constexpr double kAmp = 1e-3;
const Eigen::Vector3d kDir(1.0, -0.5, 0.25);

// u = A phi(X) d with phi = sin(pi x) sin(pi y) sin(pi z): zero on the cube's boundary.
Eigen::Vector3d exact(const Eigen::Vector3d& X) {
  return kAmp * std::sin(kPi * X[0]) * std::sin(kPi * X[1]) * std::sin(kPi * X[2]) * kDir;
}

// b = -div sigma = -(lambda + mu) grad(div u) - mu Laplace(u), N/m^3 (Hooke, small strain).
Eigen::Vector3d body_force(const Eigen::Vector3d& X, double /*t*/) {
  const double lambda = kE * kNu / ((1.0 + kNu) * (1.0 - 2.0 * kNu));
  const double mu = kE / (2.0 * (1.0 + kNu));
  Eigen::Vector3d s, c;
  for (int i = 0; i < 3; ++i) {
    s[i] = std::sin(kPi * X[i]);
    c[i] = std::cos(kPi * X[i]);
  }
  const double phi = s.prod();
  Eigen::Matrix3d hess;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i == j) {
        hess(i, j) = -kPi * kPi * phi;
      } else {
        const int k = 3 - i - j;
        hess(i, j) = kPi * kPi * c[i] * c[j] * s[k];
      }
    }
  }
  const Eigen::Vector3d grad_div = kAmp * (hess * kDir);
  const Eigen::Vector3d laplace = kAmp * (-3.0 * kPi * kPi * phi) * kDir;
  return -(lambda + mu) * grad_div - mu * laplace;
}

// ||u_h - u||_L2 / ||u||_L2 on a cube mesh with n cells per side.
double relative_l2_error(int order, int n) {
  const TetMesh mesh =
      structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), {n, n, n}, order);
  const TetSpace space(mesh);
  const auto law = materials::make_material("linear_elastic", {{"E", kE}, {"nu", kNu}});
  std::vector<int> boundary;
  for (int tag = 1; tag <= 6; ++tag) {
    const auto b = boundary_nodes(mesh, tag);
    boundary.insert(boundary.end(), b.begin(), b.end());
  }
  TetDirichlet bc;
  bc.nodes = boundary;
  TetProblemOptions opt;
  opt.formulation = Formulation::displacement;
  opt.threads = 1;
  TetProblem problem(space, *law, constant_fibres(space, Eigen::Vector3d::UnitZ()), {bc},
                     body_force, opt);
  problem.begin_step(1.0, 1.0);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size()), r;
  solver::SparseMatrix K;
  EXPECT_TRUE(problem.evaluate(u, r, &K).ok);
  Eigen::SimplicialLDLT<solver::SparseMatrix, Eigen::Upper> ldlt(K);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  u = ldlt.solve(-r);
  const Eigen::VectorXd full = problem.full_displacement(u);
  // Error integral with a degree-6 rule.
  const TetRule rule = tet_rule(6);
  const int nen = tet_nodes(order);
  double err = 0.0, norm = 0.0;
  std::vector<double> N(nen);
  std::vector<Eigen::Vector3d> dN(nen);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const auto el = mesh.element(e);
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      tet_shape_values(order, rule.points[q], N.data());
      tet_shape_gradients(order, rule.points[q], dN.data());
      Eigen::Vector3d X = Eigen::Vector3d::Zero(), uh = Eigen::Vector3d::Zero();
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int a = 0; a < nen; ++a) {
        X += N[a] * mesh.nodes[el[a]];
        uh += N[a] * full.segment<3>(3 * el[a]);
        J.noalias() += mesh.nodes[el[a]] * dN[a].transpose();
      }
      const double dv = rule.weights[q] * J.determinant();
      err += (uh - exact(X)).squaredNorm() * dv;
      norm += exact(X).squaredNorm() * dv;
    }
  }
  return std::sqrt(err / norm);
}

// Least-squares slope of log(error) against log(h).
double fitted_rate(const std::vector<int>& ns, const std::vector<double>& errors) {
  const int m = static_cast<int>(ns.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < m; ++i) {
    const double x = std::log(1.0 / ns[i]);
    const double y = std::log(errors[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

TEST(TetConvergence, LinearElasticityL2Rates) {
  for (int order : {1, 2}) {
    // Linear elements start at n = 6: on n = 4 (a half sine wave over four cells) they are
    // pre-asymptotic (measured local rate 4 -> 8: 1.73; 8 -> 12: 1.88; 12 -> 16: 1.94).
    const std::vector<int> ns =
        order == 1 ? std::vector<int>{6, 8, 12, 16} : std::vector<int>{2, 4, 6, 8};
    std::vector<double> errors;
    for (int n : ns) {
      errors.push_back(relative_l2_error(order, n));
      std::printf("order %d, n = %2d: relative L2 error %.4e\n", order, n, errors.back());
    }
    const double rate = fitted_rate(ns, errors);
    std::printf("order %d: fitted L2 rate %.3f\n", order, rate);
    EXPECT_NEAR(rate, order + 1.0, 0.2);
  }
}

}  // namespace
}  // namespace isomuscle::tet
