#include "solver/newton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "solver/setting_error.hpp"

namespace isomuscle::solver {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_non_negative(const char* key, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw SettingError(key, "must be a finite number >= 0 (got " + format_number(value) + ")");
  }
}

std::string sci(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3e", x);
  return buffer;
}

}  // namespace

void NewtonSettings::validate() const {
  if (max_iterations < 1) {
    throw SettingError("max_iterations",
                       "must be >= 1 (got " + std::to_string(max_iterations) + ")");
  }
  check_non_negative("relative_residual_tolerance", relative_residual_tolerance);
  check_non_negative("absolute_residual_tolerance", absolute_residual_tolerance);
  check_non_negative("relative_energy_tolerance", relative_energy_tolerance);
  check_non_negative("absolute_energy_tolerance", absolute_energy_tolerance);
  check_non_negative("correction_tolerance", correction_tolerance);
  if (relative_residual_tolerance == 0.0 && absolute_residual_tolerance == 0.0) {
    throw SettingError("relative_residual_tolerance",
                       "and 'absolute_residual_tolerance' cannot both be 0 (no residual would "
                       "ever be small enough)");
  }
  if (max_line_search_halvings < 0 || max_line_search_halvings > 60) {
    throw SettingError("max_line_search_halvings",
                       "must be in [0, 60] (got " + std::to_string(max_line_search_halvings) + ")");
  }
  if (max_short_steps < 0) {
    throw SettingError("max_short_steps",
                       "must be >= 0 (0: off) (got " + std::to_string(max_short_steps) + ")");
  }
  if (!(short_step > 0.0 && short_step < 1.0)) {
    throw SettingError("short_step", "must be in (0, 1) (got " + format_number(short_step) + ")");
  }
  if (!(armijo_coefficient > 0.0 && armijo_coefficient < 1.0)) {
    throw SettingError("armijo_coefficient",
                       "must be in (0, 1) (got " + format_number(armijo_coefficient) + ")");
  }
  if (!(divergence_factor > 1.0) || !std::isfinite(divergence_factor)) {
    throw SettingError("divergence_factor", "must be a finite number > 1 (got " +
                                                format_number(divergence_factor) + ")");
  }
  linear.validate();
}

bool ends_on_indefinite_tangent(const NewtonResult& result) {
  if (result.history.empty())
    return false;
  const NewtonIteration& last = result.history.back();
  return last.lu_fallback || last.shift > 0.0;
}

std::string to_string(NewtonStop stop) {
  switch (stop) {
    case NewtonStop::Converged:
      return "converged";
    case NewtonStop::MaxIterations:
      return "too many iterations";
    case NewtonStop::LineSearchFailed:
      return "line search failed";
    case NewtonStop::EvaluationFailed:
      return "evaluation failed";
    case NewtonStop::LinearSolverFailed:
      return "linear solver failed";
    case NewtonStop::Diverged:
      return "diverged";
    case NewtonStop::Stalled:
      return "stalled";
  }
  return "unknown";
}

NewtonSolver::NewtonSolver(NewtonSettings settings)
    : settings_((settings.validate(), std::move(settings))), linear_solver_(settings_.linear) {}

EvaluationStatus NewtonSolver::evaluate(NonlinearProblem& problem, const Eigen::VectorXd& u,
                                        Eigen::VectorXd& r, bool with_tangent,
                                        NewtonResult& result) {
  const auto start = std::chrono::steady_clock::now();
  EvaluationStatus status = problem.evaluate(u, r, with_tangent ? &tangent_ : nullptr);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (with_tangent) {
    ++result.tangent_evaluations;
    statistics_.tangent_seconds += seconds;
  } else {
    ++result.residual_evaluations;
    statistics_.residual_seconds += seconds;
  }
  if (!status.ok) {
    return status;
  }
  if (r.size() != u.size()) {
    throw std::logic_error("NonlinearProblem::evaluate returned a residual of size " +
                           std::to_string(r.size()) + " for " + std::to_string(u.size()) +
                           " unknowns");
  }
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    if (!std::isfinite(r[i])) {
      return EvaluationStatus::failure("evaluate() reported success but residual entry " +
                                       std::to_string(i) + " is " + format_number(r[i]));
    }
  }
  return status;
}

// Newton–Raphson with backtracking (equations in the header); units: those of the problem.
NewtonResult NewtonSolver::solve(NonlinearProblem& problem, Eigen::VectorXd& u) {
  const int n = problem.size();
  if (u.size() != n) {
    throw std::invalid_argument("NewtonSolver::solve: the initial guess has size " +
                                std::to_string(u.size()) + " but the problem has " +
                                std::to_string(n) + " unknowns");
  }
  const NewtonSettings& s = settings_;
  NewtonResult result;
  ++statistics_.solves;
  const auto finish = [&](NewtonStop stop, std::string message) {
    result.stop = stop;
    result.converged = stop == NewtonStop::Converged;
    result.message = std::move(message);
    statistics_.converged_solves += result.converged ? 1 : 0;
    statistics_.iterations += result.iterations;
    statistics_.residual_evaluations += result.residual_evaluations;
    statistics_.tangent_evaluations += result.tangent_evaluations;
    last_ends_on_indefinite_tangent_ = ends_on_indefinite_tangent(result);
    // The next solve assembles and factorises afresh; until then the tangent and its factor
    // would only hold memory, beside the predictor's (predictor_system.hpp) at the next step's
    // start. The problem makes the matrix again from its pattern (NonlinearProblem::evaluate).
    linear_solver_.release_factorization();
    tangent_ = SparseMatrix();
    return result;
  };

  // Iteration 0: residual and (almost always needed) tangent at the initial guess.
  EvaluationStatus status = evaluate(problem, u, residual_, true, result);
  if (!status.ok) {
    return finish(NewtonStop::EvaluationFailed,
                  "the problem cannot be evaluated at the initial guess: " + status.message);
  }
  const double r0 = residual_.norm();
  result.initial_residual_norm = r0;
  result.final_residual_norm = r0;
  const double residual_target =
      std::max(s.relative_residual_tolerance * r0, s.absolute_residual_tolerance);
  if (r0 <= residual_target) {
    return finish(NewtonStop::Converged, "converged at the initial guess: |r| = " + sci(r0) +
                                             " <= " + sci(residual_target));
  }
  double e1 = 0.0;
  double previous_norm = r0;           // |r_{k-1}|
  double before_previous_norm = kNaN;  // |r_{k-2}|
  double r_norm = r0;
  int short_steps = 0;  // consecutive iterations with alpha <= short_step

  for (int k = 1; k <= s.max_iterations; ++k) {
    // Linear solve K du = -r.
    const FactorizationReport& factor = linear_solver_.factorize(tangent_);
    if (!factor.ok) {
      result.min_rcond = 0.0;
      return finish(NewtonStop::LinearSolverFailed,
                    "iteration " + std::to_string(k) + ": " + factor.message);
    }
    result.min_rcond = std::min(result.min_rcond, factor.rcond);
    ++result.factorizations;
    result.lu_fallbacks += factor.fell_back && factor.method == LinearMethod::Lu ? 1 : 0;
    result.shifted_factorizations += factor.shift > 0.0 ? 1 : 0;
    rhs_ = -residual_;
    linear_solver_.solve(rhs_, du_);
    if (!du_.allFinite()) {
      return finish(NewtonStop::LinearSolverFailed,
                    "iteration " + std::to_string(k) +
                        ": the Newton correction is not finite (tangent numerically singular, "
                        "rcond estimate " +
                        sci(factor.rcond) + ")");
    }
    const double energy = std::abs(du_.dot(residual_));
    if (k == 1) {
      e1 = energy;
    }

    // Backtracking: alpha = 1, 1/2, 1/4, ...
    double alpha = 1.0;
    int halvings = 0;
    bool accepted = false;
    bool last_trial_failed_evaluation = false;
    std::string last_failure;
    const int max_halvings = s.line_search ? s.max_line_search_halvings : 0;
    for (; halvings <= max_halvings; ++halvings, alpha *= 0.5) {
      trial_u_ = u;
      trial_u_.noalias() += alpha * du_;
      status = evaluate(problem, trial_u_, trial_residual_, false, result);
      if (!status.ok) {
        last_trial_failed_evaluation = true;
        last_failure = status.message;
        continue;
      }
      last_trial_failed_evaluation = false;
      const double trial_norm = trial_residual_.norm();
      if (!s.line_search || trial_norm <= (1.0 - s.armijo_coefficient * alpha) * r_norm) {
        accepted = true;
        r_norm = trial_norm;
        break;
      }
      last_failure = "|r| = " + sci(trial_norm) + " at step " + sci(alpha);
    }
    if (!accepted) {
      const std::string where = "iteration " + std::to_string(k) + " (|r| = " + sci(r_norm) +
                                ", relative " + sci(r_norm / r0) + "): ";
      if (last_trial_failed_evaluation) {
        return finish(
            NewtonStop::EvaluationFailed,
            where +
                (s.line_search ? "no step length down to 2^-" + std::to_string(max_halvings) +
                                     " could be evaluated; last: "
                               : "the full Newton step could not be evaluated "
                                 "(line search off): ") +
                last_failure);
      }
      const double correction = du_.lpNorm<Eigen::Infinity>();
      if (s.correction_tolerance > 0.0 && correction <= s.correction_tolerance) {
        return finish(NewtonStop::Converged,
                      "converged at round-off after " + std::to_string(k - 1) +
                          " iterations: no step length reduces |r| = " + sci(r_norm) +
                          " further and the correction max|du| = " + sci(correction) +
                          " <= " + sci(s.correction_tolerance));
      }
      return finish(NewtonStop::LineSearchFailed,
                    where + "no step length down to 2^-" + std::to_string(max_halvings) +
                        " reduced |r| by the Armijo condition (last: " + last_failure +
                        "); if |r| is at round-off level, loosen the tolerances");
    }
    u.swap(trial_u_);
    residual_.swap(trial_residual_);
    result.iterations = k;
    result.final_residual_norm = r_norm;

    NewtonIteration record;
    record.iteration = k;
    record.residual_norm = r_norm;
    record.relative_residual = r_norm / r0;
    record.energy = energy;
    record.relative_energy = e1 > 0.0 ? energy / e1 : 0.0;
    record.step_length = alpha;
    record.line_search_halvings = halvings;
    record.contraction = r_norm / previous_norm;
    record.quadratic_ratio = r_norm / (previous_norm * previous_norm);
    record.observed_order =
        std::isnan(before_previous_norm)
            ? kNaN
            : std::log(r_norm / previous_norm) / std::log(previous_norm / before_previous_norm);
    record.linear_method = factor.method;
    record.lu_fallback = factor.fell_back && factor.method == LinearMethod::Lu;
    record.shift = factor.shift;
    record.rcond = factor.rcond;
    result.history.push_back(record);
    before_previous_norm = previous_norm;
    previous_norm = r_norm;

    const double energy_target =
        std::max(s.relative_energy_tolerance * e1, s.absolute_energy_tolerance);
    if (r_norm <= residual_target && energy <= energy_target) {
      return finish(NewtonStop::Converged, "converged in " + std::to_string(k) +
                                               " iterations: |r| = " + sci(r_norm) +
                                               " <= " + sci(residual_target) + ", energy " +
                                               sci(energy) + " <= " + sci(energy_target));
    }
    // Round-off floor (NewtonSettings::correction_tolerance): the residual stagnates (it fell by
    // less than half in this iteration, where a converging Newton iteration contracts by orders
    // of magnitude) while the correction is negligible.
    const double correction = alpha * du_.lpNorm<Eigen::Infinity>();
    if (s.correction_tolerance > 0.0 && correction <= s.correction_tolerance &&
        record.contraction > 0.5) {
      return finish(NewtonStop::Converged,
                    "converged at round-off in " + std::to_string(k) + " iterations: |r| = " +
                        sci(r_norm) + " stagnates and the correction max|du| = " + sci(correction) +
                        " <= " + sci(s.correction_tolerance));
    }
    // Stall (header): the last max_short_steps line searches all cut the step short and |r| has
    // not halved over them (|r| before them: r_0, or after the iteration before them).
    short_steps = alpha <= s.short_step ? short_steps + 1 : 0;
    const int window_start = k - s.max_short_steps;  // iterations before the window
    const double r_before_short =
        window_start <= 0
            ? r0
            : result.history[static_cast<std::size_t>(window_start) - 1].residual_norm;
    if (s.max_short_steps > 0 && short_steps >= s.max_short_steps && k < s.max_iterations &&
        r_norm > 0.5 * r_before_short) {
      return finish(NewtonStop::Stalled, "iteration " + std::to_string(k) + ": the last " +
                                             std::to_string(s.max_short_steps) +
                                             " line searches took steps of " + sci(s.short_step) +
                                             " or less (|r| " + sci(r_before_short) + " -> " +
                                             sci(r_norm) + ", relative " + sci(r_norm / r0) +
                                             "); the Newton direction is poor here");
    }
    if (!s.line_search && r_norm > s.divergence_factor * r0) {
      return finish(NewtonStop::Diverged,
                    "iteration " + std::to_string(k) + ": |r| = " + sci(r_norm) + " exceeds " +
                        format_number(s.divergence_factor) + " times the initial " + sci(r0));
    }
    if (k == s.max_iterations) {
      break;
    }
    // Tangent (and the same residual) at the accepted state for the next iteration.
    status = evaluate(problem, u, residual_, true, result);
    if (!status.ok) {
      return finish(
          NewtonStop::EvaluationFailed,
          "iteration " + std::to_string(k) +
              ": the accepted state could not be evaluated with its tangent: " + status.message);
    }
  }
  return finish(
      NewtonStop::MaxIterations,
      "not converged in " + std::to_string(s.max_iterations) + " iterations: |r| = " + sci(r_norm) +
          " (target " + sci(residual_target) + "), energy " +
          sci(result.history.empty() ? 0.0 : result.history.back().energy) + " (target " +
          sci(std::max(s.relative_energy_tolerance * e1, s.absolute_energy_tolerance)) + ")");
}

}  // namespace isomuscle::solver
