#pragma once
// Sparse LU factorisation P R^{-1} A Q = L U by UMFPACK (Davis, ACM TOMS 30(2) 2004), through the C
// API: symbolic analysis (column pre-ordering, frontal structure) once per pattern, numeric
// factorisation per matrix. Reads every stored entry, so the matrix must hold both triangles.
// Used for matrices that are not positive definite (the fallback when Cholesky fails) or not
// symmetric.
#include <memory>
#include <string>

#include "solver/nonlinear_problem.hpp"

namespace isomuscle::solver {

struct LuStatus {
  bool ok = false;
  bool singular = false;  // a zero pivot: the matrix is (numerically) singular
  std::string message;
};

class UmfpackLu {
 public:
  UmfpackLu();
  ~UmfpackLu();
  UmfpackLu(UmfpackLu&&) noexcept;
  UmfpackLu& operator=(UmfpackLu&&) noexcept;
  UmfpackLu(const UmfpackLu&) = delete;
  UmfpackLu& operator=(const UmfpackLu&) = delete;

  // Symbolic analysis of a's pattern (compressed, square, sorted rows). Throws std::runtime_error
  // naming the UMFPACK status when it fails.
  void analyze(const SparseMatrix& a);
  // Numeric factorisation of a, which must have the analysed pattern (the caller checks).
  LuStatus factorize(const SparseMatrix& a);
  // x = A^{-1} b with the last successful factorisation (and up to two steps of iterative
  // refinement with a copy of the factorised matrix); throws std::logic_error when there is none,
  // std::runtime_error when UMFPACK fails.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

  bool analyzed() const;
  bool factorized() const;
  // UMFPACK's reciprocal condition estimate min|U_ii| / max|U_ii| of the last factorisation.
  double rcond() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace isomuscle::solver
