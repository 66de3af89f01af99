// Newton–Raphson: the exact discrete solution of a nonlinear reaction–diffusion problem, quadratic
// convergence observed in the logged residuals, line search rescuing a problem plain Newton
// overshoots, evaluation failures rejected by halving, and the failure reasons.
#include "solver/newton.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>

#include "solver/setting_error.hpp"
#include "tests/solver/test_problems.hpp"

namespace isomuscle::solver {
namespace {

void print_history(const NewtonResult& result) {
  for (const NewtonIteration& it : result.history) {
    std::cout << "  k=" << it.iteration << " |r|/|r0|=" << it.relative_residual
              << " E/E1=" << it.relative_energy << " alpha=" << it.step_length
              << " |r_k|/|r_k-1|^2=" << it.quadratic_ratio << " order=" << it.observed_order
              << "\n";
  }
  std::cout << "  " << result.message << "\n";
}

TEST(NewtonTestProblem, TangentMatchesFiniteDifferences) {
  testing::ReactionDiffusionProblem problem(8, 50.0, 2.0);
  problem.load_factor = 0.7;
  const Eigen::VectorXd u = 0.6 * problem.exact() + 0.1 * Eigen::VectorXd::Ones(problem.size());
  Eigen::VectorXd r;
  SparseMatrix k;
  ASSERT_TRUE(problem.evaluate(u, r, &k).ok);
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(problem.size(), -1.0, 1.0);
  const double eps = 1e-6;
  Eigen::VectorXd r_plus;
  Eigen::VectorXd r_minus;
  ASSERT_TRUE(problem.evaluate(u + eps * v, r_plus, nullptr).ok);
  ASSERT_TRUE(problem.evaluate(u - eps * v, r_minus, nullptr).ok);
  const Eigen::VectorXd fd = (r_plus - r_minus) / (2.0 * eps);
  const Eigen::VectorXd kv = k.selfadjointView<Eigen::Upper>() * v;
  EXPECT_LE((kv - fd).norm(), 1e-8 * kv.norm());
}

TEST(Newton, FindsTheExactDiscreteSolutionWithQuadraticConvergence) {
  testing::ReactionDiffusionProblem problem(30, 50.0, 2.0);
  NewtonSettings settings;
  settings.relative_residual_tolerance = 1e-13;
  settings.relative_energy_tolerance = 1e-24;
  NewtonSolver newton(settings);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  const NewtonResult result = newton.solve(problem, u);
  print_history(result);
  ASSERT_TRUE(result.converged) << result.message;
  EXPECT_EQ(result.stop, NewtonStop::Converged);
  EXPECT_LE((u - problem.exact()).norm(), 1e-11 * problem.exact().norm());
  ASSERT_EQ(static_cast<int>(result.history.size()), result.iterations);

  // Quadratic convergence: over the last iterations above round-off, |r_k| / |r_{k-1}|^2 stays
  // bounded and the observed order log(|r_k|/|r_k-1|) / log(|r_k-1|/|r_k-2|) approaches 2.
  int checked = 0;
  for (const NewtonIteration& it : result.history) {
    const bool asymptotic = it.iteration >= 3 && it.relative_residual < 1e-2 &&
                            it.relative_residual > 1e-13 && it.step_length == 1.0;
    if (asymptotic) {
      EXPECT_GT(it.observed_order, 1.8) << "iteration " << it.iteration;
      EXPECT_LT(it.observed_order, 2.5) << "iteration " << it.iteration;
      ++checked;
    }
  }
  EXPECT_GE(checked, 2);

  // Every iteration used Cholesky; statistics add up.
  for (const NewtonIteration& it : result.history) {
    EXPECT_EQ(it.linear_method, LinearMethod::Cholesky);
    EXPECT_GT(it.rcond, 0.0);
  }
  EXPECT_EQ(newton.linear_solver().statistics().symbolic_analyses, 1);
  EXPECT_EQ(newton.linear_solver().statistics().cholesky_factorizations, result.iterations);
  EXPECT_EQ(result.tangent_evaluations, result.iterations);  // the last accepted state needs none
  EXPECT_EQ(newton.statistics().iterations, result.iterations);
  EXPECT_EQ(problem.evaluations, result.residual_evaluations + result.tangent_evaluations);
  EXPECT_EQ(result.factorizations, result.iterations);
  EXPECT_EQ(result.lu_fallbacks, 0);
  EXPECT_GT(result.min_rcond, 0.0);
  EXPECT_LT(result.min_rcond, 1.0);
}

TEST(Newton, IndefiniteTangentsAreFactorisedByLuAndCounted) {
  testing::DoubleWellChainProblem problem(40, 0.05);
  Eigen::VectorXd u = 0.2 * Eigen::VectorXd::LinSpaced(problem.size(), 0.5, 1.0);
  NewtonSettings settings;
  settings.absolute_residual_tolerance = 1e-14;
  NewtonSolver newton(settings);
  const NewtonResult result = newton.solve(problem, u);
  print_history(result);
  ASSERT_TRUE(result.converged) << result.message;
  EXPECT_LE(u.norm(), 1e-12);  // the solution u = 0
  EXPECT_EQ(result.lu_fallbacks, result.iterations);
  for (const NewtonIteration& it : result.history) {
    EXPECT_TRUE(it.lu_fallback);
    EXPECT_EQ(it.linear_method, LinearMethod::Lu);
  }
  const LinearSolverStatistics& stats = newton.linear_solver().statistics();
  EXPECT_EQ(stats.lu_fallbacks, result.iterations);
  EXPECT_EQ(stats.cholesky_failures, result.iterations);
  EXPECT_EQ(stats.symbolic_analyses, 1);
  EXPECT_EQ(stats.lu_symbolic_analyses, 1);
}

// From a start whose tangent is indefinite (u_i from 0.45, on the hump side of the double well
// where 3 u^2 - 1 < 0), the shift response's damped directions lead to the stable equilibrium near
// u_i = 1, where the tangent is positive definite again and the last iterations are plain Newton
// steps with quadratic convergence. The exact Newton direction (LU) converges to an equilibrium
// with some springs on the hump (an unstable one: its tangent is indefinite).
TEST(Newton, ShiftedTangentsLeadToTheStableEquilibrium) {
  testing::DoubleWellChainProblem problem(40, 0.05);
  const Eigen::VectorXd start = Eigen::VectorXd::LinSpaced(problem.size(), 0.45, 1.3);
  NewtonSettings settings;
  settings.absolute_residual_tolerance = 1e-14;
  settings.max_iterations = 40;
  settings.linear.indefinite = IndefiniteResponse::Shift;
  NewtonSolver newton(settings);
  Eigen::VectorXd u = start;
  const NewtonResult result = newton.solve(problem, u);
  print_history(result);
  ASSERT_TRUE(result.converged) << result.message;
  EXPECT_GT(u.minCoeff(), 0.9);
  EXPECT_LT(u.maxCoeff(), 1.1);
  EXPECT_GE(result.shifted_factorizations, 1);
  EXPECT_EQ(result.lu_fallbacks, 0);
  EXPECT_GT(result.history.front().shift, 0.0);
  ASSERT_GE(result.history.size(), 3u);
  for (std::size_t i = result.history.size() - 2; i < result.history.size(); ++i) {
    EXPECT_EQ(result.history[i].shift, 0.0);
    EXPECT_EQ(result.history[i].step_length, 1.0);
  }
  EXPECT_EQ(newton.linear_solver().statistics().lu_factorizations, 0);

  NewtonSettings lu_settings = settings;
  lu_settings.linear.indefinite = IndefiniteResponse::Lu;
  NewtonSolver exact(lu_settings);
  Eigen::VectorXd v = start;
  const NewtonResult lu_result = exact.solve(problem, v);
  print_history(lu_result);
  ASSERT_TRUE(lu_result.converged) << lu_result.message;
  EXPECT_LT(v.minCoeff(), 0.5);  // a spring left on the hump or in the other well
  EXPECT_GE(lu_result.lu_fallbacks, 1);
  // That equilibrium is unstable: its tangent is not positive definite.
  Eigen::VectorXd r;
  SparseMatrix k;
  ASSERT_TRUE(problem.evaluate(v, r, &k).ok);
  LinearSolverSettings no_response;
  no_response.indefinite = IndefiniteResponse::Fail;
  LinearSolver check(no_response);
  EXPECT_FALSE(check.factorize(k).ok);
}

TEST(Newton, LineSearchRescuesAProblemPlainNewtonOvershoots) {
  testing::AtanChainProblem problem(50, 0.05);
  NewtonSettings plain_settings;
  plain_settings.line_search = false;
  plain_settings.max_iterations = 30;
  NewtonSolver plain(plain_settings);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  const NewtonResult overshoot = plain.solve(problem, u);
  std::cout << "plain Newton: " << overshoot.message << "\n";
  EXPECT_FALSE(overshoot.converged);
  ASSERT_GE(overshoot.history.size(), 1u);
  EXPECT_GT(overshoot.history.front().residual_norm, overshoot.initial_residual_norm);

  NewtonSolver damped;
  u.setZero();
  const NewtonResult result = damped.solve(problem, u);
  print_history(result);
  ASSERT_TRUE(result.converged) << result.message;
  EXPECT_LT(result.history.front().step_length, 1.0);
  EXPECT_GT(result.history.front().line_search_halvings, 0);
  EXPECT_EQ(result.history.back().step_length, 1.0);
  Eigen::VectorXd r;
  ASSERT_TRUE(problem.evaluate(u, r, nullptr).ok);
  EXPECT_LE(r.norm(), 1e-8 * result.initial_residual_norm);
}

TEST(Newton, TrialStatesThatCannotBeEvaluatedAreHalvedAway) {
  // The first full Newton step from 0 (the linear solution) overshoots the cubic problem's
  // solution (max 2) past the failure bound 3.
  testing::ReactionDiffusionProblem problem(12, 50.0, 2.0);
  problem.failure_bound = 3.0;
  NewtonSolver newton;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  const NewtonResult result = newton.solve(problem, u);
  print_history(result);
  ASSERT_TRUE(result.converged) << result.message;
  EXPECT_GT(result.history.front().line_search_halvings, 0);
  EXPECT_LE((u - problem.exact()).norm(), 1e-7 * problem.exact().norm());

  // Without line search the same overshoot is an evaluation failure naming the place.
  NewtonSettings plain;
  plain.line_search = false;
  NewtonSolver plain_newton(plain);
  u.setZero();
  const NewtonResult failed = plain_newton.solve(problem, u);
  EXPECT_FALSE(failed.converged);
  EXPECT_EQ(failed.stop, NewtonStop::EvaluationFailed);
  EXPECT_NE(failed.message.find("exceeds 3"), std::string::npos) << failed.message;
  EXPECT_NE(failed.message.find("line search off"), std::string::npos) << failed.message;
}

// A problem whose tangent is 500 times too soft: every Newton correction is 500 times too long,
// the line search accepts 1/256 of it and (near the solution, where the problem is nearly linear)
// |r| falls by 5 % an iteration. Four such short steps in a
// row stop the solve as stalled (the time stepper then cuts the step); without the rule it spends
// all its iterations.
class TooSoftTangent : public NonlinearProblem {
 public:
  TooSoftTangent(NonlinearProblem& inner, double factor) : inner_(inner), factor_(factor) {}
  int size() const override { return inner_.size(); }
  void begin_step(double time, double dt) override { inner_.begin_step(time, dt); }
  EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                            SparseMatrix* tangent) override {
    const EvaluationStatus status = inner_.evaluate(u, residual, tangent);
    if (tangent != nullptr) {
      *tangent *= 1.0 / factor_;
    }
    return status;
  }
  void commit_step(const Eigen::VectorXd& u) override { inner_.commit_step(u); }

 private:
  NonlinearProblem& inner_;
  double factor_;
};

TEST(Newton, ConsecutiveShortStepsStopTheSolveAsStalled) {
  testing::ReactionDiffusionProblem inner(10, 50.0, 2.0);
  TooSoftTangent problem(inner, 500.0);
  NewtonSettings settings;
  settings.max_short_steps = 4;
  NewtonSolver newton(settings);
  // From near the solution, where the problem is nearly linear.
  const Eigen::VectorXd start = 0.9 * inner.exact();
  Eigen::VectorXd u = start;
  const NewtonResult stalled = newton.solve(problem, u);
  print_history(stalled);
  EXPECT_EQ(stalled.stop, NewtonStop::Stalled);
  // The first short step took |r| to 9 % of r_0 (the first correction's 1/512 happens to be
  // about the exact one): progress, so the window of four that stalls is iterations 2-5.
  EXPECT_EQ(stalled.iterations, settings.max_short_steps + 1);
  for (const NewtonIteration& it : stalled.history) {
    EXPECT_LE(it.step_length, settings.short_step);
  }
  EXPECT_NE(
      stalled.message.find("iteration 5: the last 4 line searches took steps of 6.250e-02 or less"),
      std::string::npos)
      << stalled.message;

  NewtonSettings patient = settings;
  patient.max_short_steps = 0;  // the default
  NewtonSolver slow(patient);
  u = start;
  const NewtonResult spent = slow.solve(problem, u);
  EXPECT_EQ(spent.stop, NewtonStop::MaxIterations);
  EXPECT_EQ(spent.iterations, patient.max_iterations);

  // Short steps that halve |r| between them are progress, not a stall: with the tangent 20 times
  // too soft the line search takes 1/16 of each correction and |r| falls by 75 % an iteration;
  // the solve converges, linearly.
  testing::ReactionDiffusionProblem inner_fine(10, 50.0, 2.0);
  TooSoftTangent less_soft(inner_fine, 20.0);
  u = start;
  const NewtonResult linear = newton.solve(less_soft, u);
  print_history(linear);
  EXPECT_TRUE(linear.converged) << linear.message;
  EXPECT_GT(linear.iterations, settings.max_short_steps);
  EXPECT_LE(linear.history[settings.max_short_steps].step_length, settings.short_step);
}

TEST(Newton, ReportsWhyItStopped) {
  testing::ReactionDiffusionProblem problem(10, 50.0, 2.0);
  NewtonSettings settings;
  settings.max_iterations = 2;
  NewtonSolver newton(settings);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  NewtonResult result = newton.solve(problem, u);
  EXPECT_EQ(result.stop, NewtonStop::MaxIterations);
  EXPECT_NE(result.message.find("not converged in 2 iterations"), std::string::npos)
      << result.message;

  // Initial guess outside the evaluable region.
  problem.failure_bound = 1.0;
  u.setConstant(5.0);
  result = newton.solve(problem, u);
  EXPECT_EQ(result.stop, NewtonStop::EvaluationFailed);
  EXPECT_NE(result.message.find("initial guess"), std::string::npos) << result.message;

  // Already in equilibrium: no iteration, no factorisation.
  problem.failure_bound = 1e300;
  u = problem.exact();
  NewtonSettings floor_settings;
  floor_settings.absolute_residual_tolerance = 1e-9;
  NewtonSolver floor_newton(floor_settings);
  result = floor_newton.solve(problem, u);
  EXPECT_TRUE(result.converged) << result.message;
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(result.factorizations, 0);
  EXPECT_EQ(result.min_rcond, 1.0);

  Eigen::VectorXd wrong_size = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(newton.solve(problem, wrong_size), std::invalid_argument);
}

// A residual carrying round-off noise of amplitude 1e-9 (erratic in u, standing in for the
// cancellation error of a nearly incompressible body, whose floor can lie above the absolute
// tolerance): the line search cannot reduce |r| below the noise. Without the correction tolerance
// the solve fails (it wanders at the floor until max_iterations, or the line search stalls); with
// it the solve is accepted once the corrections are below it, and u is then within the noise's
// reach of the exact solution (|du| ~ noise / lambda_min(K)).
class NoisyReactionDiffusion : public testing::ReactionDiffusionProblem {
 public:
  NoisyReactionDiffusion() : ReactionDiffusionProblem(8, 50.0, 2.0) {}
  EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& r,
                            SparseMatrix* tangent) override {
    const EvaluationStatus status = ReactionDiffusionProblem::evaluate(u, r, tangent);
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      r[i] += 1e-9 * std::sin(1e13 * u[i] + static_cast<double>(i));  // erratic in u
    }
    return status;
  }
};

TEST(Newton, AResidualStagnatingAtRoundOffIsConvergedOnlyWithASmallCorrection) {
  NoisyReactionDiffusion problem;
  problem.begin_step(1.0, 1.0);
  NewtonSettings settings;
  settings.relative_residual_tolerance = 1e-16;  // below the noise: unreachable
  settings.max_iterations = 50;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  NewtonResult strict = NewtonSolver(settings).solve(problem, u);
  EXPECT_FALSE(strict.converged) << strict.message;  // wanders at the floor or stalls

  settings.correction_tolerance = 1e-20;  // far below what the noise leaves: still a failure
  u.setZero();
  const NewtonResult too_tight = NewtonSolver(settings).solve(problem, u);
  EXPECT_FALSE(too_tight.converged) << too_tight.message;

  settings.correction_tolerance = 1e-8;
  u.setZero();
  const NewtonResult accepted = NewtonSolver(settings).solve(problem, u);
  EXPECT_TRUE(accepted.converged) << accepted.message;
  std::printf("%s\n", accepted.message.c_str());
  EXPECT_NE(accepted.message.find("round-off"), std::string::npos) << accepted.message;
  EXPECT_LT((u - problem.exact()).lpNorm<Eigen::Infinity>(), 1e-8);
  EXPECT_LT(accepted.final_residual_norm, 1e-7);  // the noise floor, sqrt(64) * 1e-9 ~ 8e-9
}

TEST(Newton, SettingsAreValidated) {
  const auto key_of = [](NewtonSettings settings) {
    try {
      NewtonSolver solver(settings);
    } catch (const SettingError& error) {
      return error.key();
    }
    return std::string("accepted");
  };
  NewtonSettings s;
  s.max_iterations = 0;
  EXPECT_EQ(key_of(s), "max_iterations");
  s = {};
  s.relative_residual_tolerance = -1.0;
  EXPECT_EQ(key_of(s), "relative_residual_tolerance");
  s = {};
  s.relative_residual_tolerance = 0.0;
  EXPECT_EQ(key_of(s), "relative_residual_tolerance");
  s = {};
  s.armijo_coefficient = 1.0;
  EXPECT_EQ(key_of(s), "armijo_coefficient");
  s = {};
  s.absolute_energy_tolerance = std::nan("");
  EXPECT_EQ(key_of(s), "absolute_energy_tolerance");
  s = {};
  s.correction_tolerance = -1e-9;
  EXPECT_EQ(key_of(s), "correction_tolerance");
  s = {};
  s.divergence_factor = 0.5;
  EXPECT_EQ(key_of(s), "divergence_factor");
  s = {};
  s.linear.method = LinearMethod::None;
  EXPECT_EQ(key_of(s), "method");
  EXPECT_EQ(key_of(NewtonSettings{}), "accepted");
}

}  // namespace
}  // namespace isomuscle::solver
