// The assembled tangent against central differences of the assembled residual, for a Hill muscle
// under activation (tang2009 and lu2010) and a neo-Hookean solid, in both formulations; and the
// symmetry of the tangent (the condensed mixed tangent is symmetric, so CHOLMOD applies). The
// kernels compute the upper triangle and mirror it, so the check against differences in random
// directions (which sees both triangles) is also the check that the true tangent is symmetric.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::iga {
namespace {

struct TangentCheck {
  double relative_error = 0.0;  // max over directions |K v - FD| / |K v|
};

// A 1 cm distorted rational block, face u0 fixed, random displacement of 1 % of its size.
TangentCheck check(const materials::MaterialLaw& law, Formulation formulation, double time,
                   int pressure_degree = 0) {
  geometry::NurbsVolume v = testing::distorted_rational_block(2, 2, 0.1, 5);
  std::vector<Eigen::Vector3d> pts = v.points();
  for (auto& p : pts) {
    p *= 0.01;
  }
  v = geometry::NurbsVolume(v.all_knots(), pts, v.weights());
  const Space space(v);
  const DofMap dofs(v);
  DirichletConditions bcs;
  bcs.fix("u0", nodes_of(dofs, side_control_points(v, Side::u0)));
  ProblemOptions opts;
  opts.formulation = formulation;
  opts.pressure_degree = pressure_degree;
  opts.storage = solver::MatrixStorage::Full;
  Problem problem(space, dofs, law, fibre_directions(space, FibreSpec::isocurve(0)), bcs, {}, opts);
  problem.begin_step(time, 0.01);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd u(problem.size());
  for (int i = 0; i < u.size(); ++i) {
    u[i] = 1e-4 * unit(gen);
  }
  // A stretch along x on top of the noise, so the fibres (along u = x) are active and stretched.
  for (int i = 0; i < problem.size(); ++i) {
    const int dof = problem.constraints().free_dofs()[i];
    if (dof % 3 == 0) {
      u[i] += 0.05 * dofs.position(dof / 3).x();
    }
  }
  Eigen::VectorXd r0;
  solver::SparseMatrix K;
  const solver::EvaluationStatus st = problem.evaluate(u, r0, &K);
  EXPECT_TRUE(st.ok) << st.message;
  TangentCheck out;
  const double h = 1e-7;  // m, about 1e-5 of the element size
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd dir(problem.size());
    for (int i = 0; i < dir.size(); ++i) {
      dir[i] = unit(gen);
    }
    Eigen::VectorXd rp, rm;
    EXPECT_TRUE(problem.evaluate(u + h * dir, rp, nullptr).ok);
    EXPECT_TRUE(problem.evaluate(u - h * dir, rm, nullptr).ok);
    const Eigen::VectorXd fd = (rp - rm) / (2.0 * h);
    const Eigen::VectorXd Kv = K * dir;
    out.relative_error = std::max(out.relative_error, (Kv - fd).norm() / Kv.norm());
  }
  return out;
}

TEST(Tangent, HillMusclesUnderActivationMatchCentralDifferences) {
  for (const char* model : {"tang2009", "lu2010"}) {
    const auto law = materials::make_material(model);
    const double time = 0.05;  // s: tang2009 fully active after 5 ms, lu2010 ramping (S = 50/s)
    EXPECT_GT(law->activation(time), 0.5) << model;
    for (Formulation f : {Formulation::displacement, Formulation::mixed}) {
      const TangentCheck c = check(*law, f, time);
      std::printf("%-8s %-12s: |K v - FD| / |K v| = %.2e\n", model, to_string(f), c.relative_error);
      EXPECT_LT(c.relative_error, 1e-6) << model << " " << to_string(f);
    }
  }
}

TEST(Tangent, NeoHookeanBothFormulationsAndHigherPressureDegree) {
  const auto law = materials::make_material("neo_hookean", {{"C10", 500.0}, {"K", 5.0e6}});
  for (Formulation f : {Formulation::displacement, Formulation::mixed}) {
    const TangentCheck c = check(*law, f, 0.0);
    std::printf("neo_hookean %-12s: |K v - FD| / |K v| = %.2e\n", to_string(f), c.relative_error);
    EXPECT_LT(c.relative_error, 1e-6);
  }
  const TangentCheck c1 = check(*law, Formulation::mixed, 0.0, 1);
  std::printf("neo_hookean mixed k=1    : |K v - FD| / |K v| = %.2e\n", c1.relative_error);
  EXPECT_LT(c1.relative_error, 1e-6);
}

}  // namespace
}  // namespace isomuscle::iga
