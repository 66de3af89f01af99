#pragma once
// Quasi-static time (load) stepping over [start_time, end_time] with adaptive step size:
//
//   for each step t -> t + dt: problem.begin_step(t + dt, dt); problem.predict(u); Newton from
//   there; converged  -> problem.commit_step(u), callback, and after easy_steps_to_grow consecutive
//   steps
//                 of at most easy_iterations Newton iterations dt <- min(growth_factor dt, max_dt);
//   failed     -> (diverged, too many iterations, evaluation failure, line search or linear solver
//                 failure) the cut is recorded, u is restored to the last converged state and the
//                 step is retried with dt <- cut_factor dt; when that is below min_dt the run stops
//                 with a failure result and the last converged state in u.
//
// Steps land exactly on every requested output time and on end_time: a step that would pass one
// is shortened to end on it, and when the remainder is between one and two steps it is split into
// two equal halves (no sliver steps). Shortening for an output time does not change the nominal dt
// used afterwards. Everything is deterministic: the same inputs give the same sequence of steps.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "solver/newton.hpp"
#include "solver/nonlinear_problem.hpp"

namespace isomuscle::solver {

struct TimeStepperSettings {
  double start_time = 0.0;     // s
  double end_time = 1.0;       // s
  double initial_dt = 0.1;     // s
  double min_dt = 1e-6;        // s; a cut below this ends the run
  double max_dt = 0.1;         // s
  double cut_factor = 0.5;     // in (0, 1)
  double growth_factor = 1.5;  // >= 1 (1: never grow)
  int easy_steps_to_grow = 3;  // consecutive easy steps before dt grows
  int easy_iterations = 5;     // a step converged in at most this many iterations is easy
  int max_steps = 1000000;     // converged steps plus failed attempts, a guard against endless runs
  // Times at which a step must end (for outputs); each in (start_time, end_time]; any order.
  std::vector<double> output_times;

  // Throws SettingError naming the bad setting and the valid range.
  void validate() const;
};

struct StepCut {
  int attempt = 0;       // index of the failed attempt (converged steps + earlier failures)
  double time = 0.0;     // start of the step, s
  double dt = 0.0;       // the step size that failed, s
  double next_dt = 0.0;  // the cut size tried next (below min_dt when the run stopped), s
  NewtonStop stop = NewtonStop::MaxIterations;
  std::string reason;  // Newton's message
  int newton_iterations = 0;
};

struct StepRecord {
  int step = 0;       // 1-based
  double time = 0.0;  // end of the step, s
  double dt = 0.0;    // s
  int newton_iterations = 0;
  int line_search_halvings = 0;  // summed over the iterations
  double final_residual_norm = 0.0;
  double min_rcond = 0.0;
  int lu_fallbacks = 0;
  int shifted_factorizations = 0;
  // The tangent of the last Newton iteration was not positive definite: the equilibrium reached
  // is unstable (ends_on_indefinite_tangent, newton.hpp).
  bool unstable = false;
  bool output_time = false;  // the step ended on a requested output time
};

// What the callback sees after each converged (and committed) step.
struct StepInfo {
  const StepRecord& record;
  const NewtonResult& newton;
  bool final = false;  // the step ended at end_time
};

struct TimeStepperResult {
  bool completed = false;
  std::string message;  // how the run ended, in words
  double time = 0.0;    // the last converged time, s (start_time when no step converged)
  int failed_attempts = 0;
  int newton_iterations = 0;  // over all attempts, failed ones included
  std::vector<StepRecord> steps;
  std::vector<StepCut> cuts;
};

class TimeStepper {
 public:
  using StepCallback = std::function<void(const StepInfo& info, const Eigen::VectorXd& u)>;
  // Called after each failed attempt, once its cut is recorded (u is back at the last converged
  // state): the Newton iterations of the attempt, which no converged step shows.
  using CutCallback = std::function<void(const StepCut& cut, const NewtonResult& newton)>;

  // Validates both settings (SettingError).
  explicit TimeStepper(TimeStepperSettings settings, NewtonSettings newton = {});

  // Runs from the state u at start_time (the problem's committed state). On return u is the last
  // converged state (at result.time), whether or not the run completed. on_step may be empty.
  // Throws std::invalid_argument when u has the wrong size; exceptions from the problem or the
  // callbacks propagate. on_cut may be empty.
  TimeStepperResult run(NonlinearProblem& problem, Eigen::VectorXd& u,
                        const StepCallback& on_step = {}, const CutCallback& on_cut = {});

  const TimeStepperSettings& settings() const { return settings_; }
  const NewtonSolver& newton() const { return newton_; }

 private:
  TimeStepperSettings settings_;
  NewtonSolver newton_;
};

}  // namespace isomuscle::solver
