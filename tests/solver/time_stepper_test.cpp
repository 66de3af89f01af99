// Quasi-static stepping: landing on output times, step growth, callbacks and commits; evaluation
// failures cutting the step until min_dt, with a clear failure, the cut list and the last good
// state; determinism.
#include "solver/time_stepper.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/setting_error.hpp"
#include "tests/solver/test_problems.hpp"

namespace isomuscle::solver {
namespace {

TimeStepperSettings stepping(double initial_dt, double max_dt) {
  TimeStepperSettings s;
  s.end_time = 1.0;
  s.initial_dt = initial_dt;
  s.max_dt = max_dt;
  s.min_dt = 1e-3;
  return s;
}

TEST(TimeStepper, RunsToTheEndLandingOnOutputTimes) {
  testing::ReactionDiffusionProblem problem(12, 50.0, 2.0);
  TimeStepperSettings settings = stepping(0.1, 0.25);
  settings.output_times = {0.5, 0.35};
  settings.easy_iterations = 10;
  TimeStepper stepper(settings);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  std::vector<double> times;
  std::vector<double> output_times;
  int finals = 0;
  const TimeStepperResult result =
      stepper.run(problem, u, [&](const StepInfo& info, const Eigen::VectorXd& state) {
        times.push_back(info.record.time);
        if (info.record.output_time) {
          output_times.push_back(info.record.time);
        }
        finals += info.final ? 1 : 0;
        EXPECT_TRUE(info.newton.converged);
        EXPECT_EQ(state.size(), problem.size());
      });
  std::cout << result.message << "\n  dt:";
  for (const StepRecord& step : result.steps) {
    std::cout << " " << step.dt << " (" << step.newton_iterations << ")";
  }
  std::cout << "\n";
  ASSERT_TRUE(result.completed) << result.message;
  EXPECT_EQ(result.time, 1.0);
  EXPECT_TRUE(result.cuts.empty());
  EXPECT_EQ(output_times, (std::vector<double>{0.35, 0.5}));
  EXPECT_EQ(times.back(), 1.0);
  EXPECT_EQ(finals, 1);
  EXPECT_EQ(times.size(), result.steps.size());
  EXPECT_EQ(problem.committed.size(), result.steps.size());
  EXPECT_EQ(problem.begun.size(), result.steps.size());
  // 0.1, 0.1, then 0.15 left to 0.35 split in two halves; after three easy steps the nominal dt
  // grows to 0.15 (0.075 left to 0.35, then 0.15 to 0.5), after three more to 0.225 (0.5 left to
  // the end: 0.225 would leave 0.275 < 2 * 0.225, so 0.175 twice).
  const std::vector<double> expected_dt{0.1, 0.1, 0.075, 0.075, 0.15, 0.15, 0.175, 0.175};
  ASSERT_EQ(result.steps.size(), expected_dt.size());
  for (std::size_t i = 0; i < expected_dt.size(); ++i) {
    EXPECT_NEAR(result.steps[i].dt, expected_dt[i], 1e-15) << "step " << i;
    EXPECT_LE(result.steps[i].newton_iterations, settings.easy_iterations);
  }
  // At t = 1 the state is the exact discrete solution.
  EXPECT_LE((u - problem.exact()).norm(), 1e-7 * problem.exact().norm());
}

TEST(TimeStepper, EvaluationFailureCutsTheStepAndEndsWithTheLastGoodState) {
  testing::ReactionDiffusionProblem problem(12, 50.0, 2.0);
  problem.failure_bound = 1.5;  // u* has max 2 at t = 1: the bound is reached before the end
  TimeStepperSettings settings = stepping(0.1, 0.2);
  TimeStepper stepper(settings);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  // The cut callback sees every failed attempt as it is recorded, with its Newton iterations.
  std::vector<StepCut> seen;
  int iterations_seen = 0;
  const TimeStepperResult result =
      stepper.run(problem, u, {}, [&](const StepCut& cut, const NewtonResult& newton) {
        seen.push_back(cut);
        EXPECT_EQ(static_cast<int>(newton.history.size()), cut.newton_iterations);
        EXPECT_FALSE(newton.converged);
        iterations_seen += newton.iterations;
      });
  ASSERT_EQ(seen.size(), result.cuts.size());
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].attempt, result.cuts[i].attempt);
    EXPECT_EQ(seen[i].dt, result.cuts[i].dt);
  }
  int converged_iterations = 0;
  for (const StepRecord& step : result.steps)
    converged_iterations += step.newton_iterations;
  EXPECT_EQ(iterations_seen + converged_iterations, result.newton_iterations);
  std::cout << result.message << "\n";
  for (const StepCut& cut : result.cuts) {
    std::cout << "  cut at t=" << cut.time << " dt=" << cut.dt << ": " << to_string(cut.stop)
              << "\n";
  }
  EXPECT_FALSE(result.completed);
  EXPECT_LT(result.time, 1.0);
  EXPECT_GT(result.time, 0.0);
  EXPECT_NE(result.message.find("below min_dt"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("last converged state is at t = "), std::string::npos);
  ASSERT_FALSE(result.cuts.empty());
  EXPECT_EQ(result.failed_attempts, static_cast<int>(result.cuts.size()));
  for (const StepCut& cut : result.cuts) {
    EXPECT_DOUBLE_EQ(cut.next_dt, 0.5 * cut.dt);
    EXPECT_FALSE(cut.reason.empty());
  }
  EXPECT_LT(result.cuts.back().next_dt, settings.min_dt);
  EXPECT_GE(result.cuts.back().dt, settings.min_dt);
  EXPECT_EQ(result.cuts.back().time, result.time);
  bool failure_named = false;
  for (const StepCut& cut : result.cuts) {
    failure_named = failure_named || cut.reason.find("exceeds") != std::string::npos;
  }
  EXPECT_TRUE(failure_named);

  // u is the last converged state: in equilibrium at result.time, inside the bound, committed.
  ASSERT_FALSE(problem.committed.empty());
  EXPECT_EQ(0, std::memcmp(u.data(), problem.committed.back().data(), sizeof(double) * u.size()));
  problem.begin_step(result.time, 0.0);
  Eigen::VectorXd r;
  ASSERT_TRUE(problem.evaluate(u, r, nullptr).ok);
  EXPECT_LE(r.norm(), 1e-6 * problem.exact().norm());
  // ... and the stepper got within 2 min_dt of where the solution leaves the bound.
  problem.failure_bound = 1e300;
  problem.begin_step(result.time + 2.0 * settings.min_dt, 2.0 * settings.min_dt);
  NewtonSolver newton;
  Eigen::VectorXd beyond = u;
  ASSERT_TRUE(newton.solve(problem, beyond).converged);
  EXPECT_LE(u.cwiseAbs().maxCoeff(), 1.5);
  EXPECT_GT(beyond.cwiseAbs().maxCoeff(), 1.5);
}

// A column under a compressive load growing with time, in its simplest discrete form: n lateral
// deflections u_i of a pinned chain with springs k between neighbours (K_0 = k tridiag(-1, 2, -1)),
// softened by the load t (the geometric stiffness -t I), and pushed sideways by a small force f:
//   r(u) = (K_0 - t I) u - f.
// The straight column is stable while t < t_cr = lambda_min(K_0) = 2 k (1 - cos(pi / (n + 1))), the
// Euler load of the chain; beyond it K is indefinite and every equilibrium is unstable. Newton's
// LU response converges to them (one iteration: r is linear in u).
class SofteningChainProblem : public NonlinearProblem {
 public:
  SofteningChainProblem(int n, double k) : n_(n), k_(k) {}
  int size() const override { return n_; }
  double critical_load() const { return 2.0 * k_ * (1.0 - std::cos(std::numbers::pi / (n_ + 1))); }
  void begin_step(double time, double) override { load_ = time; }
  EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& r,
                            SparseMatrix* tangent) override {
    r.resize(n_);
    for (int i = 0; i < n_; ++i) {
      r[i] = (2.0 * k_ - load_) * u[i] - 1e-3;
      if (i > 0)
        r[i] -= k_ * u[i - 1];
      if (i + 1 < n_)
        r[i] -= k_ * u[i + 1];
    }
    if (tangent != nullptr) {
      std::vector<Eigen::Triplet<double>> upper;
      for (int i = 0; i < n_; ++i) {
        upper.emplace_back(i, i, 2.0 * k_ - load_);
        if (i + 1 < n_)
          upper.emplace_back(i, i + 1, -k_);
      }
      tangent->resize(n_, n_);
      tangent->setFromTriplets(upper.begin(), upper.end());
      tangent->makeCompressed();
    }
    return EvaluationStatus::success();
  }
  void commit_step(const Eigen::VectorXd&) override {}

 private:
  int n_;
  double k_;
  double load_ = 0.0;
};

// Past the Euler load the equilibria the stepper converges to are unstable, and exactly those
// steps say so (StepRecord::unstable); a run of the isomuscle app reports them in summary.json.
TEST(TimeStepper, MarksTheStepsWhoseEquilibriumIsUnstable) {
  SofteningChainProblem problem(8, 4.0);
  const double critical = problem.critical_load();
  ASSERT_GT(critical, 0.45);
  ASSERT_LT(critical, 0.5);  // between the steps ending at 0.4 and 0.5
  // r is linear: one exact correction reaches round-off, so the residual alone decides (the
  // energy floor far above E_1 ~ 1e-5) and no second iteration searches below round-off.
  NewtonSettings newton;
  newton.absolute_residual_tolerance = 1e-12;
  newton.absolute_energy_tolerance = 1.0;
  TimeStepper stepper(stepping(0.1, 0.1), newton);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  const TimeStepperResult result = stepper.run(problem, u);
  ASSERT_TRUE(result.completed) << result.message;
  ASSERT_EQ(result.steps.size(), 10u);
  for (const StepRecord& step : result.steps) {
    EXPECT_EQ(step.unstable, step.time > critical) << "t = " << step.time;
    EXPECT_EQ(step.lu_fallbacks, step.time > critical ? 1 : 0) << "t = " << step.time;
  }
}

TEST(TimeStepper, IsDeterministic) {
  const auto run = [] {
    testing::ReactionDiffusionProblem problem(10, 50.0, 2.0);
    problem.failure_bound = 1.5;
    TimeStepper stepper(stepping(0.1, 0.2));
    Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
    TimeStepperResult result = stepper.run(problem, u);
    return std::make_pair(result, u);
  };
  const auto [a, ua] = run();
  const auto [b, ub] = run();
  ASSERT_EQ(a.steps.size(), b.steps.size());
  ASSERT_EQ(a.cuts.size(), b.cuts.size());
  for (std::size_t i = 0; i < a.steps.size(); ++i) {
    EXPECT_EQ(a.steps[i].time, b.steps[i].time);
    EXPECT_EQ(a.steps[i].newton_iterations, b.steps[i].newton_iterations);
  }
  for (std::size_t i = 0; i < a.cuts.size(); ++i) {
    EXPECT_EQ(a.cuts[i].time, b.cuts[i].time);
    EXPECT_EQ(a.cuts[i].dt, b.cuts[i].dt);
    EXPECT_EQ(a.cuts[i].reason, b.cuts[i].reason);
  }
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(0, std::memcmp(ua.data(), ub.data(), sizeof(double) * ua.size()));
}

TEST(TimeStepper, SettingsAreValidated) {
  const auto key_of = [](TimeStepperSettings settings) {
    try {
      TimeStepper stepper(settings);
    } catch (const SettingError& error) {
      return error.key();
    }
    return std::string("accepted");
  };
  TimeStepperSettings s = stepping(0.1, 0.2);
  EXPECT_EQ(key_of(s), "accepted");
  s.end_time = 0.0;
  EXPECT_EQ(key_of(s), "end_time");
  s = stepping(0.1, 0.2);
  s.min_dt = 0.2;
  EXPECT_EQ(key_of(s), "min_dt");
  s = stepping(0.1, 0.05);
  EXPECT_EQ(key_of(s), "max_dt");
  s = stepping(0.1, 0.2);
  s.cut_factor = 1.0;
  EXPECT_EQ(key_of(s), "cut_factor");
  s = stepping(0.1, 0.2);
  s.growth_factor = 0.9;
  EXPECT_EQ(key_of(s), "growth_factor");
  s = stepping(0.1, 0.2);
  s.output_times = {0.5, 1.5};
  EXPECT_EQ(key_of(s), "output_times");
  s = stepping(0.1, 0.2);
  s.initial_dt = std::nan("");
  EXPECT_EQ(key_of(s), "initial_dt");

  testing::ReactionDiffusionProblem problem(4, 1.0, 1.0);
  TimeStepper stepper(stepping(0.1, 0.2));
  Eigen::VectorXd wrong = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(stepper.run(problem, wrong), std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::solver
