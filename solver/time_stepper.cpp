#include "solver/time_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "solver/setting_error.hpp"

namespace isomuscle::solver {

namespace {

void check_finite(const char* key, double value) {
  if (!std::isfinite(value)) {
    throw SettingError(key, "must be a finite number (got " + format_number(value) + ")");
  }
}

std::string sci(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", x);
  return buffer;
}

// Step ends: requested output times and end_time, ascending, without duplicates.
std::vector<double> step_targets(const TimeStepperSettings& s) {
  std::vector<double> targets = s.output_times;
  targets.push_back(s.end_time);
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
  return targets;
}

}  // namespace

void TimeStepperSettings::validate() const {
  check_finite("start_time", start_time);
  check_finite("end_time", end_time);
  if (!(end_time > start_time)) {
    throw SettingError("end_time", "must be > start_time = " + format_number(start_time) +
                                       " (got " + format_number(end_time) + ")");
  }
  if (!(initial_dt > 0.0) || !std::isfinite(initial_dt)) {
    throw SettingError("initial_dt", "must be > 0 (got " + format_number(initial_dt) + ")");
  }
  if (!(min_dt > 0.0) || !(min_dt <= initial_dt)) {
    throw SettingError("min_dt", "must be > 0 and <= initial_dt = " + format_number(initial_dt) +
                                     " (got " + format_number(min_dt) + ")");
  }
  if (!(max_dt >= initial_dt) || !std::isfinite(max_dt)) {
    throw SettingError("max_dt", "must be >= initial_dt = " + format_number(initial_dt) +
                                     " and finite (got " + format_number(max_dt) + ")");
  }
  if (!(cut_factor > 0.0 && cut_factor < 1.0)) {
    throw SettingError("cut_factor", "must be in (0, 1) (got " + format_number(cut_factor) + ")");
  }
  if (!(growth_factor >= 1.0) || !std::isfinite(growth_factor)) {
    throw SettingError("growth_factor",
                       "must be a finite number >= 1 (got " + format_number(growth_factor) + ")");
  }
  if (easy_steps_to_grow < 1) {
    throw SettingError("easy_steps_to_grow",
                       "must be >= 1 (got " + std::to_string(easy_steps_to_grow) + ")");
  }
  if (easy_iterations < 0) {
    throw SettingError("easy_iterations",
                       "must be >= 0 (got " + std::to_string(easy_iterations) + ")");
  }
  if (max_steps < 1) {
    throw SettingError("max_steps", "must be >= 1 (got " + std::to_string(max_steps) + ")");
  }
  for (double t : output_times) {
    if (!std::isfinite(t) || !(t > start_time) || !(t <= end_time)) {
      throw SettingError("output_times",
                         "must each lie in (start_time, end_time] = (" + format_number(start_time) +
                             ", " + format_number(end_time) + "] (got " + format_number(t) + ")");
    }
  }
}

TimeStepper::TimeStepper(TimeStepperSettings settings, NewtonSettings newton)
    : settings_((settings.validate(), std::move(settings))), newton_(std::move(newton)) {}

// Adaptive quasi-static stepping (see header); times in s.
TimeStepperResult TimeStepper::run(NonlinearProblem& problem, Eigen::VectorXd& u,
                                   const StepCallback& on_step, const CutCallback& on_cut) {
  if (u.size() != problem.size()) {
    throw std::invalid_argument("TimeStepper::run: the initial state has size " +
                                std::to_string(u.size()) + " but the problem has " +
                                std::to_string(problem.size()) + " unknowns");
  }
  const TimeStepperSettings& s = settings_;
  const std::vector<double> targets = step_targets(s);
  const auto is_output_time = [&](double t) {
    return std::find(s.output_times.begin(), s.output_times.end(), t) != s.output_times.end();
  };

  TimeStepperResult result;
  result.time = s.start_time;
  Eigen::VectorXd committed = u;
  double t = s.start_time;
  double dt_nominal = s.initial_dt;
  int easy_count = 0;
  std::size_t target_index = 0;
  int attempts = 0;

  while (t < s.end_time) {
    if (attempts >= s.max_steps) {
      result.message = "stopped after max_steps = " + std::to_string(s.max_steps) +
                       " step attempts at t = " + sci(t) + " (end_time " + sci(s.end_time) +
                       "); raise max_steps or the step sizes";
      u = committed;
      return result;
    }
    while (targets[target_index] <= t) {
      ++target_index;
    }
    const double target = targets[target_index];
    const double remaining = target - t;
    double dt = dt_nominal;
    bool lands = false;
    if (remaining <= dt * (1.0 + 1e-9)) {
      dt = remaining;
      lands = true;
    } else if (remaining < 2.0 * dt) {
      dt = 0.5 * remaining;  // two equal steps instead of a full one and a sliver
    }
    const double t_new = lands ? target : t + dt;

    ++attempts;
    problem.begin_step(t_new, dt);
    // A failed predictor leaves u unchanged: Newton then starts from the committed state.
    (void)problem.predict(u);
    const NewtonResult newton = newton_.solve(problem, u);
    result.newton_iterations += newton.iterations;

    if (newton.converged) {
      problem.commit_step(u);
      committed = u;
      t = t_new;
      result.time = t;
      StepRecord record;
      record.step = static_cast<int>(result.steps.size()) + 1;
      record.time = t;
      record.dt = dt;
      record.newton_iterations = newton.iterations;
      for (const NewtonIteration& it : newton.history) {
        record.line_search_halvings += it.line_search_halvings;
      }
      record.final_residual_norm = newton.final_residual_norm;
      record.min_rcond = newton.min_rcond;
      record.lu_fallbacks = newton.lu_fallbacks;
      record.shifted_factorizations = newton.shifted_factorizations;
      record.unstable = ends_on_indefinite_tangent(newton);
      record.output_time = lands && is_output_time(t);
      result.steps.push_back(record);
      if (on_step) {
        on_step(StepInfo{result.steps.back(), newton, t == s.end_time}, u);
      }
      easy_count = newton.iterations <= s.easy_iterations ? easy_count + 1 : 0;
      if (easy_count >= s.easy_steps_to_grow) {
        dt_nominal = std::min(dt_nominal * s.growth_factor, s.max_dt);
        easy_count = 0;
      }
      continue;
    }

    // Failed: back to the last converged state, cut the step.
    u = committed;
    easy_count = 0;
    ++result.failed_attempts;
    StepCut cut;
    cut.attempt = attempts - 1;
    cut.time = t;
    cut.dt = dt;
    cut.next_dt = dt * s.cut_factor;
    cut.stop = newton.stop;
    cut.reason = newton.message;
    cut.newton_iterations = newton.iterations;
    result.cuts.push_back(cut);
    if (on_cut) {
      on_cut(result.cuts.back(), newton);
    }
    if (cut.next_dt < s.min_dt) {
      result.message = "the step from t = " + sci(t) + " failed with dt = " + sci(dt) + " (" +
                       to_string(newton.stop) + ": " + newton.message +
                       "); the next cut, dt = " + sci(cut.next_dt) +
                       ", is below min_dt = " + sci(s.min_dt) +
                       ". The last converged state is at t = " + sci(t) + " after " +
                       std::to_string(result.steps.size()) + " steps and " +
                       std::to_string(result.cuts.size()) + " cuts";
      return result;
    }
    dt_nominal = cut.next_dt;
  }
  result.completed = true;
  result.message = "reached t = " + sci(t) + " in " + std::to_string(result.steps.size()) +
                   " steps (" + std::to_string(result.newton_iterations) + " Newton iterations, " +
                   std::to_string(result.cuts.size()) + " cuts)";
  return result;
}

}  // namespace isomuscle::solver
