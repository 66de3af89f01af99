// Quadratic Newton convergence on a shrink solid: the barrel of SPEC §5 (rational circle surface,
// closed seam, collapsed axis, merged DOFs), p = 2, the tang2009 muscle with activation off
// (passive), mixed formulation (kappa/mu = 2/D / (2 b c) ~ 7e5), end v0 fixed, end v1 pulled
// 1.25 mm along the axis per step, each step started from Problem::predict (the linearised
// Dirichlet predictor; without it the first Newton step inverts elements at kappa/mu ~ 7e5). The
// residual history is logged; Newton must show an observed order near 2 before round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geometry/shapes.hpp"
#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::iga {
namespace {

TEST(NewtonConvergence, PassiveStretchOfShrinkBarrelIsQuadratic) {
  const geometry::NurbsVolume vol = testing::shrink_barrel(2, {1, 1, 1});
  const Space space(vol);
  const DofMap dofs(vol);
  EXPECT_GT(dofs.num_merged_nodes(), 0);
  const auto law = materials::make_material("tang2009", {{"n2", 0.0}});
  DirichletConditions bcs;
  bcs.fix("end v0", nodes_of(dofs, side_control_points(vol, Side::v0)));
  bcs.move_with_velocity("end v1", nodes_of(dofs, side_control_points(vol, Side::v1)),
                         Eigen::Vector3d(0, 0, 1.25e-3));  // m per unit pseudo-time
  Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::isocurve(1)), bcs);
  EXPECT_EQ(problem.formulation(), Formulation::mixed);
  solver::NewtonSettings settings = testing::tight_newton(1e-10);
  settings.absolute_residual_tolerance = 1e-12;  // N; round-off floor ~1e-13 here
  settings.line_search = false;
  solver::NewtonSolver newton(settings);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  int quadratic_observations = 0;
  for (int step = 1; step <= 2; ++step) {
    problem.begin_step(step, 1.0);
    const solver::EvaluationStatus predicted = problem.predict(u);
    ASSERT_TRUE(predicted.ok) << predicted.message;
    const solver::NewtonResult r = newton.solve(problem, u);
    for (const auto& it : r.history) {
      std::printf("    (iteration %d: %s, rcond %.2e)\n", it.iteration,
                  solver::to_string(it.linear_method).c_str(), it.rcond);
    }
    ASSERT_TRUE(r.converged) << r.message << " min rcond " << r.min_rcond;
    std::printf("step %d (end moved %.2f mm): %s\n", step, 1.25 * step, r.message.c_str());
    for (const auto& it : r.history) {
      std::printf(
          "  iteration %d: |r| = %.3e N, |r_k|/|r_k-1| = %.2e, |r_k|/|r_k-1|^2 = %.2e, "
          "order %.2f\n",
          it.iteration, it.residual_norm, it.contraction, it.quadratic_ratio, it.observed_order);
      // Order estimates from residuals well above the round-off floor.
      if (it.iteration >= 3 && it.residual_norm > 1e-9 && std::isfinite(it.observed_order)) {
        EXPECT_GT(it.observed_order, 1.7) << "step " << step << " iteration " << it.iteration;
        ++quadratic_observations;
      }
    }
    EXPECT_LE(r.iterations, 8);
    problem.commit_step(u);
  }
  EXPECT_GT(quadratic_observations, 0);
  // The barrel got longer and kept its volume (near incompressibility).
  const double V0 = space.reference_volume();
  const double V = problem.current_volume(problem.committed_displacement());
  std::printf("volume change %.2e (relative)\n", V / V0 - 1.0);
  EXPECT_LT(std::abs(V / V0 - 1.0), 1e-4);
  // The lumped volumes of the unstable mode's metric: int R_a dV per node, positive also for the
  // nodes merged on the collapsed centreline, and summing to V0 (partition of unity).
  const Eigen::VectorXd lumped = problem.lumped_volumes();
  ASSERT_EQ(lumped.size(), dofs.num_nodes());
  EXPECT_GT(lumped.minCoeff(), 0.0);
  EXPECT_NEAR(lumped.sum(), V0, 1e-12 * V0);
}

}  // namespace
}  // namespace isomuscle::iga
