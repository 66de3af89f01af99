#include "iga/linear_elasticity.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace isomuscle::iga {

LinearElasticityProblem::LinearElasticityProblem(const Space& space, const DofMap& dofs,
                                                 double lambda, double mu,
                                                 const DirichletConditions& conditions, Loads loads,
                                                 int threads)
    : space_(space),
      dofs_(dofs),
      lambda_(lambda),
      mu_(mu),
      loads_(std::move(loads)),
      threads_(threads),
      constraints_(dofs, conditions) {
  if (!(mu > 0.0) || !(3.0 * lambda + 2.0 * mu > 0.0)) {
    throw std::invalid_argument(
        "linear elasticity: need mu > 0 and 3 lambda + 2 mu > 0, got "
        "lambda = " +
        std::to_string(lambda) + ", mu = " + std::to_string(mu));
  }
  const int nel = space_.num_elements();
  const int nen = space_.functions_per_element();
  element_all_dofs_.resize(nel);
  std::vector<std::vector<int>> free_lists(nel);
  for (int e = 0; e < nel; ++e) {
    const auto cps = space_.control_points(e);
    for (int a = 0; a < nen; ++a) {
      for (int k = 0; k < 3; ++k) {
        const int dof = DofMap::dof(dofs_.node(cps[a]), k);
        element_all_dofs_[e].push_back(dof);
        free_lists[e].push_back(constraints_.free_index(dof));
      }
    }
  }
  pattern_ = solver::SparsityPattern(solver::ElementDofs(free_lists), constraints_.num_free());
  pattern_all_ = solver::SparsityPattern(solver::ElementDofs(element_all_dofs_), dofs_.num_dofs(),
                                         solver::MatrixStorage::Full);
  colouring_ = solver::ElementColouring(solver::ElementDofs(element_all_dofs_));
  begin_step(0.0, 0.0);
}

void LinearElasticityProblem::begin_step(double time, double /*dt*/) {
  time_ = time;
  assemble_external_forces(space_, dofs_, loads_, time_, f_ext_);
}

Eigen::VectorXd LinearElasticityProblem::full_displacement(const Eigen::VectorXd& u) const {
  Eigen::VectorXd full;
  constraints_.expand(u, time_, full);
  return full;
}

// r = K u_full - f restricted to the free DOFs; K_e = int B^T D B dV (header).
void LinearElasticityProblem::assemble_matrices() {
  const int nen = space_.functions_per_element();
  const int n = 3 * nen;
  const int nthreads = solver::resolve_thread_count(threads_);
  std::vector<Eigen::MatrixXd> ke(nthreads, Eigen::MatrixXd(n, n));
  // Per thread: the six products P_ij = sum_q dV g_i g_j^T (n_en x n_en, i <= j) of the gradient
  // components g_i = (dR_a/dX_i)_a, from which K_e follows in one pass (Hughes 2.8 written
  // blockwise):
  //   K(3a+i, 3b+j) = lambda P_ij(a,b) + mu P_ji(a,b) + mu delta_ij sum_k P_kk(a,b).
  std::vector<std::array<Eigen::MatrixXd, 6>> products(nthreads);
  for (auto& p : products) {
    for (auto& m : p) {
      m.setZero(nen, nen);
    }
  }
  std::vector<Eigen::Matrix<double, 3, Eigen::Dynamic>> scaled(
      nthreads, Eigen::Matrix<double, 3, Eigen::Dynamic>(3, nen));
  constexpr int kPair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  K_free_ = pattern_.make_matrix();
  K_all_ = pattern_all_.make_matrix();
  auto body = [&](int e, int t) -> solver::EvaluationStatus {
    Eigen::MatrixXd& k = ke[t];
    auto& P = products[t];
    for (auto& m : P) {
      m.setZero();
    }
    for (int q = 0; q < space_.points_per_element(); ++q) {
      const auto grad = space_.gradients(e, q);
      const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> G(grad[0].data(), 3, nen);
      scaled[t].noalias() = space_.dv(e, q) * G;
      for (int m = 0; m < 6; ++m) {
        P[m].noalias() += scaled[t].row(kPair[m][0]).transpose() * G.row(kPair[m][1]);
      }
    }
    auto product = [&](int i, int j, int a, int b) {
      // P_ij(a, b) with P_ji = P_ij^T.
      for (int m = 0; m < 6; ++m) {
        if (kPair[m][0] == i && kPair[m][1] == j) {
          return P[m](a, b);
        }
        if (kPair[m][0] == j && kPair[m][1] == i) {
          return P[m](b, a);
        }
      }
      return 0.0;
    };
    for (int b = 0; b < nen; ++b) {
      for (int a = 0; a < nen; ++a) {
        const double trace = P[0](a, b) + P[1](a, b) + P[2](a, b);
        for (int j = 0; j < 3; ++j) {
          for (int i = 0; i < 3; ++i) {
            k(3 * a + i, 3 * b + j) = lambda_ * product(i, j, a, b) + mu_ * product(j, i, a, b) +
                                      (i == j ? mu_ * trace : 0.0);
          }
        }
      }
    }
    pattern_.add_element_matrix(e, k, K_free_.valuePtr());
    pattern_all_.add_element_matrix(e, k, K_all_.valuePtr());
    return solver::EvaluationStatus::success();
  };
  solver::for_each_element_coloured(colouring_, threads_, body);
  assembled_ = true;
}

// r = K u_full - f restricted to the free DOFs; K_e = int B^T D B dV (header).
solver::EvaluationStatus LinearElasticityProblem::evaluate(const Eigen::VectorXd& u,
                                                           Eigen::VectorXd& residual,
                                                           solver::SparseMatrix* tangent) {
  if (u.size() != size()) {
    throw std::invalid_argument("LinearElasticityProblem::evaluate: vector of size " +
                                std::to_string(u.size()) + ", expected " + std::to_string(size()));
  }
  if (!assembled_) {
    assemble_matrices();
  }
  Eigen::VectorXd u_full;
  constraints_.expand(u, time_, u_full);
  const Eigen::VectorXd diff = K_all_ * u_full - f_ext_;
  constraints_.restrict_to_free(diff, residual);
  if (tangent != nullptr) {
    *tangent = K_free_;
  }
  return solver::EvaluationStatus::success();
}

}  // namespace isomuscle::iga
