#pragma once
// The linear system of the linearised Dirichlet predictor (iga::Problem::predict,
// tet::TetProblem::predict): K_ff du_f = rhs with the tangent at the committed state. A matrix with
// the problem's sparsity pattern and a linear solver (one symbolic analysis) kept between steps;
// the matrix and the numeric factor are freed after each solve, so that they and Newton's (its
// factor freed at the end of each Newton solve) are never held together.
#include <Eigen/Core>
#include <memory>

#include "solver/linear_solver.hpp"
#include "solver/matrix_storage.hpp"
#include "solver/nonlinear_problem.hpp"
#include "solver/sparsity_pattern.hpp"

namespace isomuscle::solver {

class PredictorSystem {
 public:
  // The matrix with the pattern's structure and zero values, to assemble the tangent into.
  SparseMatrix& zeroed_matrix(const SparsityPattern& pattern);
  // Factorises the assembled matrix (storage as the problem's) and solves K du = rhs. A failure
  // (the factorisation, a non-finite du) says why, prefixed "predictor: ".
  EvaluationStatus solve(MatrixStorage storage, const Eigen::VectorXd& rhs, Eigen::VectorXd& du);

 private:
  SparseMatrix matrix_;
  std::unique_ptr<LinearSolver> solver_;
};

}  // namespace isomuscle::solver
