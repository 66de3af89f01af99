// Newton's tangent pass at the state its line search has just evaluated lets the law read the
// trial history instead of updating it again (materials::PointInput::trial_is_current, set by
// iga::Problem::evaluate and internal_force when the free values are those of the last successful
// evaluation in this step). On an active barrel (tang2009, fibres along the isocurves) the pass is
// offered exactly where it may be: at every accepted state's tangent and the reaction probes'
// internal force at the converged state, and nowhere else (not at a step's first iterate, not
// after an evaluation elsewhere, not in a new step). The solution is bitwise that of the same
// solve with the offer refused.
#include <gtest/gtest.h>

#include <memory>

#include "geometry/shapes.hpp"
#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"
#include "solver/newton.hpp"
#include "tests/support/offer_counting_law.hpp"

namespace isomuscle::iga {
namespace {

using materials::MaterialLaw;
using test_support::OfferCountingLaw;

struct ActiveBarrel {
  geometry::NurbsVolume vol = testing::shrink_barrel(2, {1, 2, 1});
  Space space{vol};
  DofMap dofs{vol};
  std::unique_ptr<MaterialLaw> muscle = materials::make_material("tang2009");
  OfferCountingLaw law;
  DirichletConditions bcs;
  std::unique_ptr<Problem> problem;
  explicit ActiveBarrel(bool refuse) : law(*muscle, refuse) {
    bcs.fix("end v0", nodes_of(dofs, side_control_points(vol, Side::v0)));
    ProblemOptions options;
    options.threads = 1;
    problem = std::make_unique<Problem>(
        space, dofs, law, fibre_directions(space, FibreSpec::isocurve(1)), bcs, Loads{}, options);
  }
};

TEST(TrialReuse, TangentPassAtTheAcceptedStateReadsTheTrialHistoryWithTheSameSolution) {
  ActiveBarrel reading(false), refusing(true);
  const long points = reading.space.num_points();
  solver::NewtonSolver newton_a(testing::tight_newton(1e-10)),
      newton_b(testing::tight_newton(1e-10));
  const int n = reading.problem->size();
  Eigen::VectorXd u_a = Eigen::VectorXd::Zero(n), u_b = u_a;
  long passes_at_evaluated_states = 0;
  const double dt = 2e-3;  // the activation ramp (full after 5 ms) and after it
  for (int step = 1; step <= 5; ++step) {
    for (ActiveBarrel* b : {&reading, &refusing}) {
      b->problem->begin_step(step * dt, dt);
    }
    ASSERT_TRUE(reading.problem->predict(u_a).ok);
    ASSERT_TRUE(refusing.problem->predict(u_b).ok);
    const solver::NewtonResult a = newton_a.solve(*reading.problem, u_a);
    const solver::NewtonResult b = newton_b.solve(*refusing.problem, u_b);
    ASSERT_TRUE(a.converged) << "step " << step << ": " << a.message;
    ASSERT_TRUE(b.converged) << "step " << step << ": " << b.message;
    EXPECT_EQ(a.iterations, b.iterations) << "step " << step;
    EXPECT_EQ(u_a, u_b) << "step " << step << ": not bitwise the same solution";
    // Every tangent but the first of a solve comes at the state the line search accepted.
    passes_at_evaluated_states += a.tangent_evaluations - 1;
    // The reaction probes' internal force at the converged state, before the commit.
    Eigen::VectorXd f_a, f_b;
    ASSERT_TRUE(reading.problem->internal_force(u_a, f_a).ok);
    ASSERT_TRUE(refusing.problem->internal_force(u_b, f_b).ok);
    EXPECT_EQ(f_a, f_b) << "step " << step;
    ++passes_at_evaluated_states;
    reading.problem->commit_step(u_a);
    refusing.problem->commit_step(u_b);
  }
  EXPECT_EQ(reading.law.offered.load(), passes_at_evaluated_states * points);
  EXPECT_EQ(refusing.law.offered.load(), reading.law.offered.load());
}

TEST(TrialReuse, NotOfferedAfterAnEvaluationElsewhereOrInANewStep) {
  ActiveBarrel barrel(false);
  Problem& problem = *barrel.problem;
  const int n = problem.size();
  Eigen::VectorXd u = Eigen::VectorXd::Constant(n, 1e-6), elsewhere = 2.0 * u, r;
  solver::SparseMatrix K;
  problem.begin_step(1e-3, 1e-3);
  ASSERT_TRUE(problem.evaluate(u, r, nullptr).ok);
  ASSERT_TRUE(problem.evaluate(elsewhere, r, nullptr).ok);
  ASSERT_TRUE(problem.evaluate(u, r, &K).ok);
  EXPECT_EQ(barrel.law.offered.load(), 0) << "offered after an evaluation at other values";
  problem.begin_step(2e-3, 1e-3);
  ASSERT_TRUE(problem.evaluate(u, r, &K).ok);
  EXPECT_EQ(barrel.law.offered.load(), 0) << "offered in a new step";
  // Evaluated again at the same values in the same step: offered at every point.
  ASSERT_TRUE(problem.evaluate(u, r, &K).ok);
  EXPECT_EQ(barrel.law.offered.load(), barrel.space.num_points());
}

}  // namespace
}  // namespace isomuscle::iga
