#pragma once
// The linear solver of each Newton iteration, K du = -r: CHOLMOD supernodal Cholesky for the
// symmetric tangent and LU alone for non-symmetric matrices. When Cholesky finds the tangent not
// positive definite (past a limit point, a material with a locally indefinite tangent, or a state
// far from equilibrium in the first iterations of a long step) one of three responses is chosen:
//   Lu     the same matrix by UMFPACK LU: the exact Newton direction, which also converges to an
//          unstable equilibrium;
//   Shift  Cholesky of K + beta I with beta = tau mean|K_ii| (modified Newton, Nocedal & Wright,
//          Numerical Optimization, 2nd ed., section 3.4, "Cholesky with added multiple of the
//          identity"): tau from shift_initial, times shift_growth until the factorisation
//          succeeds. The direction is a descent direction of the potential energy wherever one
//          exists, damped along the soft modes like Levenberg-Marquardt, and it costs a few
//          Cholesky factorisations instead of an LU factorisation of the same matrix, whose
//          factor holds 2 times the nonzeros (bench_cholmod, BM_LuFallback against
//          BM_ShiftFallback, 23k-51k unknowns: LU 2.9-25 s, the failed Cholesky and two shifted
//          attempts 0.8-6.7 s, 3.6-4.5 times less);
//   Fail   no factorisation: the Newton solve stops and the time stepper cuts the step.
// Which one suits a problem is measured in README.md ("Solver"): LU is the default because
// Shift cannot converge to an equilibrium whose tangent is itself indefinite.
// The symbolic analysis is done once per sparsity pattern: each factorize() compares the pattern
// with the analysed one (O(nnz)) and analyses again only when it changed.
// Counters and per-phase times are kept for the run summary.
#include <memory>
#include <string>

#include "solver/cholmod_cholesky.hpp"
#include "solver/matrix_storage.hpp"
#include "solver/nonlinear_problem.hpp"
#include "solver/umfpack_lu.hpp"

namespace isomuscle::solver {

enum class LinearMethod { None, Cholesky, Lu };
enum class IndefiniteResponse { Fail, Lu, Shift };
// "none", "Cholesky (CHOLMOD)", "LU (UMFPACK)".
std::string to_string(LinearMethod method);
// "fail", "lu", "shift" (the scene file's words).
std::string to_string(IndefiniteResponse response);

struct LinearSolverSettings {
  // Which entries the matrices hold (matrix_storage.hpp).
  MatrixStorage storage = MatrixStorage::Upper;
  // The first factorisation tried: Cholesky needs a symmetric matrix (it reads the upper
  // triangle); Lu takes any matrix (a non-symmetric one needs Full storage; an Upper one is
  // expanded to both triangles).
  LinearMethod method = LinearMethod::Cholesky;
  // With Cholesky: what to do when the matrix is not positive definite (header comment).
  IndefiniteResponse indefinite = IndefiniteResponse::Lu;
  CholeskyOrdering ordering = CholeskyOrdering::Default;
  // Threads of the BLAS under CHOLMOD (blas_threads.hpp), set when the solver is made; 0 leaves
  // the BLAS as it is. One by default: for the sizes of these models (< 1e5 DOFs) threads gain
  // little and OpenBLAS's spinning threads cost up to 10x on a busy machine.
  int blas_threads = 1;
  // Shift: the first tau tried is shift_initial, or, when the last shifted factorisation
  // succeeded with tau', max(shift_initial, tau' / shift_growth) (the shift relaxes as the
  // iterates approach a stable equilibrium, as the damping of Levenberg-Marquardt does); at most
  // shift_attempts factorisations, each tau shift_growth times the last. The mean diagonal of a
  // condensed nearly incompressible tangent is of the bulk modulus's scale (kappa / mu ~ 1e6 in the
  // muscle scenes) while its soft, possibly negative, modes are of the shear modulus's: the first
  // tau is far below 1e-6 for that reason, and the sequence reaches 1e3.
  double shift_initial = 1e-9;
  double shift_growth = 10.0;
  int shift_attempts = 13;

  // Throws SettingError ("'method' must be Cholesky or Lu ...").
  void validate() const;
};

// Wall-clock seconds per phase, summed over calls.
struct LinearSolverTimings {
  double symbolic = 0.0;  // CHOLMOD analyses and UMFPACK symbolic analyses
  double numeric = 0.0;   // numeric factorisations (including failed Cholesky attempts)
  double lu = 0.0;        // the part of numeric spent in UMFPACK
  double shifted = 0.0;   // the part of numeric spent in Cholesky attempts of K + beta I
  double solve = 0.0;     // triangular solves
};

struct LinearSolverStatistics {
  int symbolic_analyses = 0;        // CHOLMOD analyses (one per distinct pattern)
  int lu_symbolic_analyses = 0;     // UMFPACK analyses (one per pattern that needed LU)
  int pattern_changes = 0;          // factorize() calls whose pattern differed from the last
  int cholesky_factorizations = 0;  // attempts, successful or not
  // Of the matrices themselves, not of their shifted copies: not positive definite (or another
  // CHOLMOD failure), so with Lu or Shift the number of indefinite tangents met.
  int cholesky_failures = 0;
  int lu_factorizations = 0;
  int lu_fallbacks = 0;            // LU factorisations made because Cholesky failed
  int shifted_factorizations = 0;  // successful Cholesky factorisations of K + beta I
  int failed_shifts = 0;           // attempts of K + beta I that failed (beta too small)
  double max_shift = 0.0;          // the largest tau of those
  int failures = 0;                // factorize() calls that produced no usable factorisation
  int solves = 0;
  LinearSolverTimings time;
};

struct FactorizationReport {
  bool ok = false;
  LinearMethod method = LinearMethod::None;
  // Cholesky of the matrix failed and the factorisation is LU of it (method Lu) or Cholesky of
  // the shifted matrix (method Cholesky, shift > 0).
  bool fell_back = false;
  double shift = 0.0;  // tau of K + tau mean|K_ii| I when the shifted matrix was factorised
  // Reciprocal condition estimate of the factorisation used: CHOLMOD (min/max diag L)^2 or UMFPACK
  // min/max |U_ii|; 0 when no factorisation succeeded.
  double rcond = 0.0;
  std::string message;  // why not ok, or why LU was used; empty otherwise
};

class LinearSolver {
 public:
  explicit LinearSolver(LinearSolverSettings settings = {});
  ~LinearSolver();
  LinearSolver(LinearSolver&&) noexcept;
  LinearSolver& operator=(LinearSolver&&) noexcept;
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  // Factorises a (square, compressed, storage as in the settings). Returns ok = false with a
  // message when no factorisation succeeded (non-finite entry, singular matrix, not positive
  // definite with IndefiniteResponse::Fail, or no shift up to the last attempt sufficed). After a
  // shifted factorisation, solve() solves with K + beta I, not with a. Throws std::invalid_argument
  // when a is not square/compressed, or holds entries below the diagonal with Upper storage.
  FactorizationReport factorize(const SparseMatrix& a);
  // x = A^{-1} b with the last successful factorisation (std::logic_error when there is none).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Frees the numeric factorisation (CHOLMOD's L, UMFPACK's L and U), keeping the symbolic
  // analyses: between uses, so that two solvers of one problem (Newton's and the predictor's) do
  // not hold a factor each. solve() throws until the next factorize; the statistics stay.
  void release_factorization();

  const FactorizationReport& last_report() const;
  const LinearSolverStatistics& statistics() const;
  const LinearSolverSettings& settings() const;
  // CHOLMOD's view of the analysed pattern: nonzeros of L, factorisation flops, ordering used.
  const CholmodCholesky& cholesky() const;
  // UMFPACK's view of its last analysis and factorisation: strategy, nonzeros of L and U.
  const UmfpackLu& lu() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace isomuscle::solver
