#pragma once
// Sparse LU factorisation P R^{-1} A Q = L U by UMFPACK (Davis, ACM TOMS 30(2) 2004), through the C
// API: symbolic analysis (column pre-ordering, frontal structure) once per pattern, numeric
// factorisation per matrix. Reads every stored entry, so the matrix must hold both triangles.
// Used for matrices that are not positive definite (the fallback when Cholesky fails) or not
// symmetric.
#include <memory>
#include <string>
#include <vector>

#include "solver/nonlinear_problem.hpp"

namespace isomuscle::solver {

struct LuStatus {
  bool ok = false;
  bool singular = false;  // a zero pivot: the matrix is (numerically) singular
  std::string message;
};

// How the symbolic analysis orders the matrix.
struct LuAnalysisOptions {
  // The matrix is symmetric (both triangles stored): use UMFPACK's symmetric strategy (an ordering
  // of A + A^T, diagonal pivots preferred), which keeps the fill near a Cholesky factor's. Left to
  // itself UMFPACK picks its strategy from the values it is given at analysis time; given a
  // pattern whose diagonal it cannot see as nonzero it chooses the unsymmetric strategy, whose
  // fronts grew to 12 times the flops on the DAO's tangent (and did not finish in 16 minutes at
  // 27509 unknowns, where the symmetric one takes 8 s).
  bool symmetric = false;
  // A fill-reducing order to start from instead of UMFPACK's own AMD/COLAMD (a permutation of
  // 0..n-1, e.g. CHOLMOD's for the same pattern); empty: UMFPACK's.
  std::vector<int> column_order;
};

class UmfpackLu {
 public:
  UmfpackLu();
  ~UmfpackLu();
  UmfpackLu(UmfpackLu&&) noexcept;
  UmfpackLu& operator=(UmfpackLu&&) noexcept;
  UmfpackLu(const UmfpackLu&) = delete;
  UmfpackLu& operator=(const UmfpackLu&) = delete;

  // Symbolic analysis of a's pattern (compressed, square, sorted rows; UMFPACK also reads the
  // values, so pass the matrix to be factorised). Throws std::invalid_argument when
  // options.column_order is not a permutation of 0..n-1, std::runtime_error naming the UMFPACK
  // status when the analysis fails.
  void analyze(const SparseMatrix& a, const LuAnalysisOptions& options = {});
  // Numeric factorisation of a, which must have the analysed pattern (the caller checks).
  LuStatus factorize(const SparseMatrix& a);
  // x = A^{-1} b with the last successful factorisation (and up to two steps of iterative
  // refinement with a copy of the factorised matrix); throws std::logic_error when there is none,
  // std::runtime_error when UMFPACK fails.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Frees the numeric factorisation (L and U), keeping the symbolic analysis; solve() throws
  // until the next factorize.
  void release_numeric();

  bool analyzed() const;
  bool factorized() const;
  // UMFPACK's reciprocal condition estimate min|U_ii| / max|U_ii| of the last factorisation.
  double rcond() const;
  // Whether the last analysis chose the symmetric strategy.
  bool symmetric_strategy() const;
  // Nonzeros of L plus U of the last successful factorisation (0 before one).
  double factor_nonzeros() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace isomuscle::solver
