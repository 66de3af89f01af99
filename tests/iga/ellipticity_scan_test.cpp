// The strong-ellipticity scan of a committed state (Problem::committed_ellipticity,
// continuum/point_ellipticity.hpp): on a distorted rational block deformed homogeneously (a linear
// field, which the NURBS space reproduces exactly), every quadrature point must give what the law
// gives at that F, with the point's own fibre and the history committed BEFORE the step, at the
// step's time and size, as the mixed formulation evaluates it (the isochoric part). Two steps of
// the active tang2009 muscle, shortened 15 % then 30 % along the fibres' mean direction with a
// shear: the scan is of the committed state (its value moves from 1.15 mu to 1.88 mu between the
// steps). At these states the smallest wave's stiffness hardly depends on the fibre (the same to
// 3e-6 mu at every point, though the fibres' directions differ), so the value does not tell the
// fibre or the history apart, and this test does not claim to.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"
#include "materials/strong_ellipticity.hpp"

namespace isomuscle::iga {
namespace {

TEST(EllipticityScan, EveryPointGivesTheLawsValueAtTheCommittedState) {
  const geometry::NurbsVolume vol = testing::distorted_rational_block(2, 2, 0.2, 5);
  const Space space(vol);
  const DofMap dofs(vol);
  const auto law = materials::make_material("tang2009");
  ProblemOptions options;
  options.formulation = Formulation::mixed;
  const std::vector<Eigen::Vector3d> fibres = fibre_directions(space, FibreSpec::isocurve(1));
  Problem problem(space, dofs, *law, fibres, DirichletConditions{}, {}, options);
  ASSERT_EQ(problem.size(), 3 * dofs.num_nodes());

  const std::size_t points = fibres.size();
  const std::size_t hs = static_cast<std::size_t>(law->history_size());
  std::vector<double> history(points * hs);
  for (std::size_t p = 0; p < points; ++p)
    law->initial_history(std::span<double>(history.data() + p * hs, hs));

  // Shortening along y (the fibres' mean direction) with a shear: 15 % then 30 %, 2.5 ms steps.
  const double dt = 2.5e-3;
  for (int step = 1; step <= 2; ++step) {
    Eigen::Matrix3d F;
    F << 1.0 / std::sqrt(1.0 - 0.15 * step), 0.03 * step, 0.0,  //
        0.0, 1.0 - 0.15 * step, 0.0,                            //
        0.02 * step, 0.0, 1.0 / std::sqrt(1.0 - 0.15 * step);
    Eigen::VectorXd u(problem.size());
    for (int node = 0; node < dofs.num_nodes(); ++node)
      u.segment<3>(3 * node) = (F - Eigen::Matrix3d::Identity()) * dofs.position(node);
    const double time = step * dt;
    problem.begin_step(time, dt);
    Eigen::VectorXd residual;
    ASSERT_TRUE(problem.evaluate(u, residual, nullptr).ok);
    problem.commit_step(u);

    const std::vector<continuum::PointEllipticity> scan = problem.committed_ellipticity();
    ASSERT_EQ(scan.size(), points);
    std::vector<double> trial(hs);
    double smallest = INFINITY, largest = -INFINITY;
    for (std::size_t p = 0; p < points; ++p) {
      materials::PointInput in;
      in.F = F;
      in.fibre = fibres[p];
      in.time = time;
      in.dt = dt;
      in.history = std::span<const double>(history.data() + p * hs, hs);
      materials::PointResult result;
      result.history = trial;
      ASSERT_EQ(law->evaluate_isochoric(in, result, true), materials::PointStatus::ok);
      const double expected =
          materials::refined_isochoric_ellipticity(F, result.S, result.tangent).smallest;
      ASSERT_NEAR(scan[p].smallest, expected, 1e-9 * law->shear_modulus())
          << "step " << step << ", point " << p;
      std::copy(trial.begin(), trial.end(), history.begin() + static_cast<long>(p * hs));
      smallest = std::min(smallest, expected);
      largest = std::max(largest, expected);
    }
    const double mu = law->shear_modulus();
    std::printf("step %d: e from %.6f to %.6f mu over the points\n", step, smallest / mu,
                largest / mu);
    // Stretched across the fibres, the exponential matrix stiffens the transverse waves.
    EXPECT_GT(smallest, (step == 1 ? 1.1 : 1.8) * mu) << "step " << step;
    EXPECT_LT(largest, (step == 1 ? 1.2 : 1.95) * mu) << "step " << step;
  }
}

}  // namespace
}  // namespace isomuscle::iga
