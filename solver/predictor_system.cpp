#include "solver/predictor_system.hpp"

#include <algorithm>

namespace isomuscle::solver {

SparseMatrix& PredictorSystem::zeroed_matrix(const SparsityPattern& pattern) {
  if (!pattern.matches(matrix_))
    matrix_ = pattern.make_matrix();
  else
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0);
  return matrix_;
}

EvaluationStatus PredictorSystem::solve(MatrixStorage storage, const Eigen::VectorXd& rhs,
                                        Eigen::VectorXd& du) {
  if (!solver_) {
    LinearSolverSettings settings;
    settings.storage = storage;
    solver_ = std::make_unique<LinearSolver>(settings);
  }
  const FactorizationReport report = solver_->factorize(matrix_);
  if (report.ok)
    solver_->solve(rhs, du);
  // Newton assembles and factorises its own tangent next: without this the run would hold two
  // factors and two matrices. The matrix is made again from the pattern at the next step (an
  // O(nnz) copy; the same pattern, so no new symbolic analysis).
  solver_->release_factorization();
  matrix_ = SparseMatrix();
  if (!report.ok)
    return EvaluationStatus::failure("predictor: " + report.message);
  if (!du.allFinite())
    return EvaluationStatus::failure("predictor: non-finite increment");
  return EvaluationStatus::success();
}

}  // namespace isomuscle::solver
