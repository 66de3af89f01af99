#pragma once
// Newton–Raphson for r(u) = 0 on a NonlinearProblem, with a backtracking line search:
//
//   K(u_k) du_k = -r(u_k),   u_{k+1} = u_k + alpha_k du_k,
//   alpha_k = 2^-m, the first m = 0, 1, ... with evaluate(u_k + alpha du_k) ok and (Armijo on the
//   merit 1/2 |r|^2, for which du_k is a descent direction of slope -|r_k|^2)
//   |r(u_k + alpha du_k)| <= (1 - c alpha) |r(u_k)|.
//
// A trial state whose evaluation fails (J <= 0, a failed local material solve) is rejected like one
// that does not decrease the residual, so the step is halved away from inverted elements.
//
// Convergence needs both (the residual and energy criteria of Bathe, Finite Element Procedures):
//   residual  |r_k| <= max(rtol |r_0|, atol)
//   energy    E_k = |du_k . r_{k-1}| <= max(etol E_1, eatol)   (the correction times the residual
//             it was computed from; E scales with |r|^2, so etol ~ rtol^2 to 1e4 rtol^2)
// The residual is evaluated before the tangent: a trial state is evaluated without tangent and
// the tangent is assembled only when another iteration follows.
//
// A solve whose line search keeps cutting the step short has stalled: the Newton direction is poor
// at these states (a tangent that is indefinite or nearly singular along a soft mode, a time step
// too long for the nonlinearity), each iteration costs a tangent, a factorisation and up to ten
// residuals, and it reduces |r| by about the step length alpha only. After max_short_steps
// consecutive iterations with alpha <= short_step that have not halved |r| together, the solve
// stops (NewtonStop::Stalled), so that the time stepper cuts the step at once instead of after
// max_iterations. On the DAO's 1 mm tetrahedral run with the jaw sliding (validation/suite/
// README.md, 2026-12-05) two of the three attempts that failed stalled so by their 7th iteration
// instead of going on to the 20th, no converged step did, and the run took 204 instead of 220
// iterations and 12 instead of 29 LU factorisations to the same result.
//
// For each iteration the history keeps |r_k|, E_k, alpha_k, the contraction |r_k| / |r_{k-1}|, the
// quadratic ratio |r_k| / |r_{k-1}|^2 (bounded for quadratic convergence) and the observed order
// log(|r_k| / |r_{k-1}|) / log(|r_{k-1}| / |r_{k-2}|) (tends to 2).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "solver/linear_solver.hpp"
#include "solver/nonlinear_problem.hpp"

namespace isomuscle::solver {

struct NewtonSettings {
  int max_iterations = 20;
  double relative_residual_tolerance = 1e-8;  // rtol, of |r_0| at the start of the solve
  double absolute_residual_tolerance = 0.0;   // atol, residual units (e.g. N): the floor
  double relative_energy_tolerance = 1e-12;   // etol, of E_1
  double absolute_energy_tolerance = 0.0;     // eatol, energy units (e.g. N mm): the floor
  // Round-off acceptance: when the residual has reached its round-off floor (which can lie above
  // atol) it stops decreasing: no step length reduces it, or an iteration reduces it by less than
  // half. If the Newton correction is then no larger than this in every entry (units of u, e.g.
  // m), u is known as well as the arithmetic allows: the solve counts as converged and says so.
  // A small correction alone is not enough (a stiff volumetric mode can carry a large residual
  // with a tiny correction). 0 = off.
  double correction_tolerance = 0.0;
  bool line_search = true;
  int max_line_search_halvings = 10;  // smallest step 2^-10
  // Stall: max_short_steps consecutive steps of at most short_step (0 = off, the default here: a
  // solve on its own has no recourse, and a crawl can end in quadratic convergence, as in
  // tests/tet/test_tet_barrel.cpp's 21 iterations; the scene runs set 4, where a cut follows).
  int max_short_steps = 0;
  double short_step = 1.0 / 16.0;
  double armijo_coefficient = 1e-4;  // c in (0, 1)
  // Without line search: stop when |r_k| > divergence_factor * |r_0|.
  double divergence_factor = 1e6;
  LinearSolverSettings linear;

  // Throws SettingError naming the bad setting.
  void validate() const;
};

enum class NewtonStop {
  Converged,
  MaxIterations,
  LineSearchFailed,    // no step 2^-m, m <= max halvings, reduced |r| (states evaluated fine)
  EvaluationFailed,    // the problem could not be evaluated (at u_0, or at every trial step)
  LinearSolverFailed,  // singular tangent, or non-finite entries
  Diverged,            // |r| grew past divergence_factor |r_0| (no line search)
  Stalled,             // max_short_steps consecutive short line-search steps
};
// "converged", "too many iterations", ...
std::string to_string(NewtonStop stop);

struct NewtonIteration {
  int iteration = 0;               // k, 1-based
  double residual_norm = 0.0;      // |r_k| after the step
  double relative_residual = 0.0;  // |r_k| / |r_0|
  double energy = 0.0;             // E_k = |du_k . r_{k-1}|
  double relative_energy = 0.0;    // E_k / E_1
  double step_length = 1.0;        // alpha_k
  int line_search_halvings = 0;    // m
  double contraction = 0.0;        // |r_k| / |r_{k-1}|
  double quadratic_ratio = 0.0;    // |r_k| / |r_{k-1}|^2
  double observed_order = 0.0;     // NaN for k = 1 (needs three residuals)
  LinearMethod linear_method = LinearMethod::None;
  bool lu_fallback = false;  // Cholesky failed, LU used
  double shift = 0.0;  // Cholesky failed, K + shift mean|K_ii| I factorised (linear_solver.hpp)
  double rcond = 0.0;  // of the factorisation used
};

struct NewtonResult {
  bool converged = false;
  NewtonStop stop = NewtonStop::MaxIterations;
  std::string message;  // the outcome in words, with the numbers that decided it
  int iterations = 0;   // Newton corrections applied
  double initial_residual_norm = 0.0;
  double final_residual_norm = 0.0;
  int residual_evaluations = 0;  // evaluate() calls without tangent
  int tangent_evaluations = 0;   // evaluate() calls with tangent
  int factorizations = 0;        // successful factorisations of the tangent
  int lu_fallbacks = 0;
  int shifted_factorizations = 0;
  // Smallest rcond of this solve's factorisations; 0 after a failed one, 1 (neutral for a minimum
  // over steps) when none was needed.
  double min_rcond = 1.0;
  std::vector<NewtonIteration> history;
};

// Whether the factorisation of the solve's last iteration found the tangent not positive definite
// (Cholesky failed; LU or a shift was used). For a converged solve that tangent is the one at the
// last iterate but one, which differs from the equilibrium by the last, converged correction: the
// equilibrium found is unstable (it has a direction of falling potential energy, past a bifurcation
// or a limit point), unless its smallest eigenvalue is so near zero that the correction moved it
// across. Newton with the LU response converges to such equilibria; see linear_solver.hpp.
bool ends_on_indefinite_tangent(const NewtonResult& result);

// Totals over the lifetime of a NewtonSolver (for the run summary).
struct NewtonStatistics {
  int solves = 0;
  int converged_solves = 0;
  int iterations = 0;
  int residual_evaluations = 0;
  int tangent_evaluations = 0;
  double residual_seconds = 0.0;  // in evaluate() without tangent
  double tangent_seconds = 0.0;   // in evaluate() with tangent
};

class NewtonSolver {
 public:
  // Validates the settings (SettingError).
  explicit NewtonSolver(NewtonSettings settings = {});

  // Solves r(u) = 0 from the initial guess u (size problem.size()). On return u holds the last
  // accepted iterate: the solution when converged. The same SparseMatrix object is passed as the
  // tangent at every call of one solver, so a problem may keep its pattern there and overwrite
  // only the values. Throws std::invalid_argument when u has the wrong size.
  NewtonResult solve(NonlinearProblem& problem, Eigen::VectorXd& u);

  const NewtonSettings& settings() const { return settings_; }
  const NewtonStatistics& statistics() const { return statistics_; }
  const LinearSolver& linear_solver() const { return linear_solver_; }
  // ends_on_indefinite_tangent of the last solve's result, for a problem's commit_step (which runs
  // before the time stepper hands the result on).
  bool last_solve_ends_on_indefinite_tangent() const { return last_ends_on_indefinite_tangent_; }

 private:
  // evaluate() with timing, counting and a check that an ok residual is finite.
  EvaluationStatus evaluate(NonlinearProblem& problem, const Eigen::VectorXd& u, Eigen::VectorXd& r,
                            bool with_tangent, NewtonResult& result);

  NewtonSettings settings_;
  LinearSolver linear_solver_;
  NewtonStatistics statistics_;
  SparseMatrix tangent_;
  Eigen::VectorXd residual_;
  Eigen::VectorXd trial_u_;
  Eigen::VectorXd trial_residual_;
  Eigen::VectorXd rhs_;
  Eigen::VectorXd du_;
  bool last_ends_on_indefinite_tangent_ = false;
};

}  // namespace isomuscle::solver
