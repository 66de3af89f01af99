#pragma once
// The interface a discretisation (iga/, tet/) offers to Newton and the time stepper (MFEM's
// NonlinearForm: residual "Mult", tangent "GetGradient"). Unknowns are the *free* degrees of
// freedom only: prescribed (Dirichlet) values are applied by the problem itself in begin_step, so
// the tangent handed to the linear solver is the reduced, symmetric matrix.
//
// Any auxiliary fields of a mixed formulation (element-wise pressure and dilatation) are condensed
// inside the problem and are functions of u, so Newton sees displacements only.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

namespace isomuscle::solver {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

struct EvaluationStatus {
  bool ok = true;
  std::string message;  // why not ok, naming the place (element, quadrature point, value)
  static EvaluationStatus success() { return {}; }
  static EvaluationStatus failure(std::string why) { return {false, std::move(why)}; }
};

class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;

  // Number of free unknowns.
  virtual int size() const = 0;

  // Starts the step to time t = time with size dt: prescribed values and loads at t. Called again
  // with a smaller dt when a step is cut back (the committed state is unchanged by a failed step).
  virtual void begin_step(double time, double dt) = 0;

  // Residual r(u) = f_int(u) - f_ext(t) of the free unknowns; when tangent != nullptr also
  // K = dr/du. The sparsity pattern of K is the same at every call (so a symbolic factorisation is
  // reused). Never returns NaN with ok status: an inverted element (J <= 0) or a failed local
  // material solve returns a failure naming the place.
  // The tangent holds the storage the linear solver is set for (MatrixStorage::Upper by default:
  // the upper triangle only, as SparsityPattern builds it). NewtonSolver passes the same matrix
  // object at every call of one solve and empties it between solves (to free its memory), so a
  // problem gives it its pattern when it does not have it (SparsityPattern::matches, make_matrix)
  // and otherwise only overwrites the values.
  virtual EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                                    SparseMatrix* tangent) = 0;

  // Predictor for the step set up by begin_step, called once before Newton: may move u (the
  // committed free values on entry) towards the solution at the new time, e.g. the linearised
  // response to the prescribed increment (iga::Problem). On failure u must be left unchanged;
  // Newton then starts from it. The default predicts nothing.
  virtual EvaluationStatus predict(Eigen::VectorXd& u) {
    (void)u;
    return EvaluationStatus::success();
  }

  // Makes the state at u (material history) the committed state: called once per converged step.
  virtual void commit_step(const Eigen::VectorXd& u) = 0;
};

}  // namespace isomuscle::solver
