#pragma once
// Small-strain isotropic linear elasticity on the IGA space, as a NonlinearProblem whose residual
// is affine, r(u) = K u - f(t): the verification problem of the manufactured-solution convergence
// study (tests/iga) and a cheap reference. Kernel (Hughes, The Finite Element Method, 2.7–2.8):
//   K_e = int B^T D B dV,  B the small-strain Voigt operator of dR/dX (engineering shears),
//   D = lambda m m^T + mu diag(2, 2, 2, 1, 1, 1),  m = (1, 1, 1, 0, 0, 0);
// loads from loads.hpp, Dirichlet values from ConstrainedDofs (u = 0 initial guess, one Newton
// step solves it exactly). Assembled once (with the same pattern, colouring and threads as Problem)
// on the first evaluation; later evaluations are a sparse matrix-vector product.
#include <Eigen/Core>

#include "iga/boundary_conditions.hpp"
#include "iga/dof_map.hpp"
#include "iga/loads.hpp"
#include "iga/space.hpp"
#include "solver/element_colouring.hpp"
#include "solver/nonlinear_problem.hpp"
#include "solver/sparsity_pattern.hpp"

namespace isomuscle::iga {

class LinearElasticityProblem : public solver::NonlinearProblem {
 public:
  // lambda, mu: Lamé constants (Pa), mu > 0 and 3 lambda + 2 mu > 0 (std::invalid_argument
  // otherwise). space and dofs must outlive the problem.
  LinearElasticityProblem(const Space& space, const DofMap& dofs, double lambda, double mu,
                          const DirichletConditions& conditions, Loads loads = {}, int threads = 0);

  int size() const override { return constraints_.num_free(); }
  void begin_step(double time, double dt) override;
  solver::EvaluationStatus evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                                    solver::SparseMatrix* tangent) override;
  void commit_step(const Eigen::VectorXd& /*u*/) override {}

  const ConstrainedDofs& constraints() const { return constraints_; }
  Eigen::VectorXd full_displacement(const Eigen::VectorXd& u) const;

 private:
  const Space& space_;
  const DofMap& dofs_;
  double lambda_, mu_;
  Loads loads_;
  int threads_;
  ConstrainedDofs constraints_;
  std::vector<std::vector<int>> element_all_dofs_;
  solver::SparsityPattern pattern_;      // free x free (the tangent)
  solver::SparsityPattern pattern_all_;  // all x all, full storage (the residual K u)
  solver::ElementColouring colouring_;
  bool assembled_ = false;
  solver::SparseMatrix K_free_, K_all_;
  void assemble_matrices();
  double time_ = 0.0;
  Eigen::VectorXd f_ext_;
};

}  // namespace isomuscle::iga
