#pragma once
// The linear solver of each Newton iteration, K du = -r: CHOLMOD supernodal Cholesky for the
// symmetric tangent, with UMFPACK LU as the fallback when Cholesky finds the matrix not positive
// definite (past a limit point, or a material with a locally indefinite tangent), and LU alone for
// non-symmetric matrices. The symbolic analysis is done once per sparsity pattern: each factorize()
// compares the pattern with the analysed one (O(nnz)) and analyses again only when it changed.
// Counters and per-phase times are kept for the run summary.
#include <memory>
#include <string>

#include "solver/cholmod_cholesky.hpp"
#include "solver/matrix_storage.hpp"
#include "solver/nonlinear_problem.hpp"
#include "solver/umfpack_lu.hpp"

namespace isomuscle::solver {

enum class LinearMethod { None, Cholesky, Lu };
// "none", "Cholesky (CHOLMOD)", "LU (UMFPACK)".
std::string to_string(LinearMethod method);

struct LinearSolverSettings {
  // Which entries the matrices hold (matrix_storage.hpp).
  MatrixStorage storage = MatrixStorage::Upper;
  // The first factorisation tried: Cholesky needs a symmetric matrix (it reads the upper
  // triangle); Lu takes any matrix (a non-symmetric one needs Full storage; an Upper one is
  // expanded to both triangles).
  LinearMethod method = LinearMethod::Cholesky;
  // With Cholesky: when it fails (not positive definite), factorise the same matrix by LU.
  bool lu_fallback = true;
  CholeskyOrdering ordering = CholeskyOrdering::Default;
  // Threads of the BLAS under CHOLMOD (blas_threads.hpp), set when the solver is made; 0 leaves
  // the BLAS as it is. One by default: for the sizes of these models (< 1e5 DOFs) threads gain
  // little and OpenBLAS's spinning threads cost up to 10x on a busy machine.
  int blas_threads = 1;

  // Throws SettingError ("'method' must be Cholesky or Lu ...").
  void validate() const;
};

// Wall-clock seconds per phase, summed over calls.
struct LinearSolverTimings {
  double symbolic = 0.0;  // CHOLMOD analyses and UMFPACK symbolic analyses
  double numeric = 0.0;   // numeric factorisations (including failed Cholesky attempts)
  double solve = 0.0;     // triangular solves
};

struct LinearSolverStatistics {
  int symbolic_analyses = 0;        // CHOLMOD analyses (one per distinct pattern)
  int lu_symbolic_analyses = 0;     // UMFPACK analyses (one per pattern that needed LU)
  int pattern_changes = 0;          // factorize() calls whose pattern differed from the last
  int cholesky_factorizations = 0;  // attempts, successful or not
  int cholesky_failures = 0;        // not positive definite (or another CHOLMOD failure)
  int lu_factorizations = 0;
  int lu_fallbacks = 0;  // LU factorisations made because Cholesky failed
  int failures = 0;      // factorize() calls that produced no usable factorisation
  int solves = 0;
  LinearSolverTimings time;
};

struct FactorizationReport {
  bool ok = false;
  LinearMethod method = LinearMethod::None;
  bool fell_back = false;  // Cholesky failed and LU was used
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
  // message when no factorisation succeeded (non-finite entry, singular matrix, or not positive
  // definite without fallback). Throws std::invalid_argument when a is not square/compressed, or
  // holds entries below the diagonal with Upper storage.
  FactorizationReport factorize(const SparseMatrix& a);
  // x = A^{-1} b with the last successful factorisation (std::logic_error when there is none).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

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
