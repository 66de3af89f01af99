#pragma once
// Sparse Cholesky factorisation A = P^T L L^T P of a symmetric positive definite matrix by
// CHOLMOD's supernodal method (Chen, Davis, Hager, Rajamanickam, ACM TOMS 35(3) 2008), through the
// C API. The symbolic analysis (fill-reducing ordering P and supernodal structure of L) is done
// once per sparsity pattern; numeric factorisations reuse it. Only the upper triangle of the matrix
// is read (stype = +1), so Upper and Full storage both work.
//
// The raw C API was chosen over Eigen::CholmodSupernodalLLT (which calls the same CHOLMOD routines)
// for what Eigen 3.4 does not expose: the rough condition estimate cholmod_rcond, the column at
// which a not-positive-definite matrix fails, the ordering method, and solves into reused
// workspace (cholmod_solve2); bench/bench_cholmod.cpp measures both.
#include <memory>
#include <string>
#include <vector>

#include "solver/nonlinear_problem.hpp"

namespace isomuscle::solver {

enum class CholeskyOrdering {
  Default,  // CHOLMOD's choice: AMD, then METIS when AMD's fill is high (keeps the smaller L)
  Amd,      // approximate minimum degree only
  Metis,    // METIS nested dissection only
  Nesdis,   // CHOLMOD's nested dissection (METIS + constrained minimum degree)
};

struct CholeskyStatus {
  bool ok = false;
  bool not_positive_definite = false;  // the leading minor of order failed_column + 1 is not > 0
  int failed_column = -1;
  std::string message;
};

class CholmodCholesky {
 public:
  explicit CholmodCholesky(CholeskyOrdering ordering = CholeskyOrdering::Default);
  ~CholmodCholesky();
  CholmodCholesky(CholmodCholesky&&) noexcept;
  CholmodCholesky& operator=(CholmodCholesky&&) noexcept;
  CholmodCholesky(const CholmodCholesky&) = delete;
  CholmodCholesky& operator=(const CholmodCholesky&) = delete;

  // Symbolic analysis of the pattern of a (compressed, square; values unused). Throws
  // std::runtime_error when CHOLMOD fails (e.g. out of memory), naming the CHOLMOD status.
  void analyze(const SparseMatrix& a);
  // Numeric factorisation of a + shift I (cholmod_factorize_p's beta; the matrix is not copied),
  // a with the analysed pattern (the caller checks). shift = 0: of a itself.
  CholeskyStatus factorize(const SparseMatrix& a, double shift = 0.0);
  // x = A^{-1} b with the last successful factorisation. Throws std::logic_error when there is
  // none.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  // Frees the numeric factor (L's values, the bulk of the memory), keeping the symbolic analysis
  // for the next factorize; solve() throws until then. Nothing happens without a factor.
  void release_numeric();

  bool analyzed() const;
  bool factorized() const;
  // CHOLMOD's rough reciprocal condition estimate (min diag(L) / max diag(L))^2 of the last
  // factorisation (0 when it failed). Cheap, and only an estimate: it may exceed the true
  // 1 / cond_2(A) by orders of magnitude, but it falls to 0 as A approaches singularity.
  double rcond() const;
  // From the last analysis: nonzeros of L and the flop count of the numeric factorisation.
  double factor_nonzeros() const;
  double factor_flops() const;
  // The ordering the last analysis used: "AMD", "METIS", "NESDIS", ...
  std::string ordering_used() const;
  // The fill-reducing permutation P of the last analysis (row k of P A P^T is row
  // permutation()[k] of A); empty before the first analysis. The LU fallback reuses it.
  std::vector<int> permutation() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace isomuscle::solver
