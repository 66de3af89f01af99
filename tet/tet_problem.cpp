#include "tet/tet_problem.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "continuum/problem_setup.hpp"

namespace isomuscle::tet {

void TetProblemOptions::validate() const {
  if (pressure_degree != 0 && pressure_degree != 1) {
    throw std::invalid_argument("pressure_degree " + std::to_string(pressure_degree) +
                                " (valid: 0 = constant, 1 = linear discontinuous per element)");
  }
  if (threads < 0) {
    throw std::invalid_argument("threads must be >= 0 (0 = OpenMP default)");
  }
}

TetProblem::TetProblem(const TetSpace& space, const materials::MaterialLaw& law,
                       std::vector<Eigen::Vector3d> fibres, std::vector<TetDirichlet> conditions,
                       VectorField body_force, TetProblemOptions options)
    : space_(space),
      law_(law),
      fibres_(std::move(fibres)),
      conditions_(std::move(conditions)),
      body_force_(std::move(body_force)),
      options_(options) {
  options_.validate();
  const TetMesh& mesh = space_.mesh();
  // automatic: mixed for every law with a volumetric split (no kappa/mu threshold).
  formulation_ = continuum::resolve_formulation(options_.formulation, law_, 0.0);
  continuum::check_unit_fibres(fibres_, space_.num_points(), "TetProblem");
  // DOF numbering: prescribed DOFs marked, the others numbered in node order.
  const int ndof = 3 * mesh.num_nodes();
  std::vector<char> fixed(ndof, 0);
  for (std::size_t c = 0; c < conditions_.size(); ++c) {
    for (int n : conditions_[c].nodes) {
      if (n < 0 || n >= mesh.num_nodes()) {
        throw std::invalid_argument("Dirichlet condition " + std::to_string(c) + " names node " +
                                    std::to_string(n) + " of " + std::to_string(mesh.num_nodes()));
      }
      for (int k = 0; k < 3; ++k) {
        fixed[3 * n + k] = fixed[3 * n + k] || conditions_[c].components[k];
      }
    }
  }
  free_index_.assign(ndof, solver::kPrescribed);
  for (int d = 0; d < ndof; ++d) {
    if (!fixed[d]) {
      free_index_[d] = num_free_++;
    }
  }
  const int nel = mesh.num_elements();
  const int nen = space_.nodes_per_element();
  const int nqp = space_.points_per_element();
  element_dofs_.resize(nel);
  std::vector<std::vector<int>> free_lists(nel);
  for (int e = 0; e < nel; ++e) {
    const auto el = mesh.element(e);
    for (int a = 0; a < nen; ++a) {
      for (int k = 0; k < 3; ++k) {
        element_dofs_[e].push_back(3 * el[a] + k);
        free_lists[e].push_back(free_index_[3 * el[a] + k]);
      }
    }
  }
  pattern_ = solver::SparsityPattern(solver::ElementDofs(free_lists), num_free_, options_.storage,
                                     options_.scatter);
  colouring_ = solver::ElementColouring(solver::ElementDofs(element_dofs_));
  // Pressure space: phi = 1, or (1, xi, eta, zeta) at the reference points; M_e factorised once.
  pressure_size_ = options_.pressure_degree == 0 ? 1 : 4;
  const int m = pressure_size_;
  if (formulation_ == Formulation::mixed) {
    pressure_values_.resize(static_cast<std::size_t>(nel) * nqp * m);
    mass_.resize(nel);
    mass_matrix_.resize(nel);
    for (int e = 0; e < nel; ++e) {
      Eigen::MatrixXd M = Eigen::MatrixXd::Zero(m, m);
      for (int q = 0; q < nqp; ++q) {
        double* phi = pressure_values_.data() + (static_cast<std::size_t>(e) * nqp + q) * m;
        phi[0] = 1.0;
        for (int i = 1; i < m; ++i) {
          phi[i] = space_.rule().points[q][i - 1];
        }
        const Eigen::Map<const Eigen::VectorXd> p(phi, m);
        M.noalias() += space_.dv(e)[q] * p * p.transpose();
      }
      mass_[e].compute(M);
      mass_matrix_[e] = M;
      if (mass_[e].info() != Eigen::Success) {
        throw std::invalid_argument("TetProblem: the pressure mass matrix of element " +
                                    std::to_string(e) +
                                    " is not positive definite (use pressure_degree 0 or a "
                                    "quadrature rule with more points)");
      }
    }
  }
  workspaces_.assign(solver::resolve_thread_count(options_.threads), ElementWorkspace(nen, nqp, m));
  if (formulation_ == Formulation::mixed) {
    bases_.resize(space_.num_elements(), m, 3 * nen);
  }
  history_size_ = law_.history_size();
  history_committed_.assign(static_cast<std::size_t>(space_.num_points()) * history_size_, 0.0);
  for (int i = 0; history_size_ > 0 && i < space_.num_points(); ++i) {
    law_.initial_history(std::span<double>(
        history_committed_.data() + static_cast<std::size_t>(i) * history_size_, history_size_));
  }
  history_trial_ = history_committed_;
  history_previous_ = history_committed_;
  committed_full_.setZero(ndof);
  u_full_.setZero(ndof);
  begin_step(0.0, 0.0);
}

// Prescribed values and the body force at t = time (NonlinearProblem::begin_step):
// f_ext,a = sum_e sum_q N_a(xi_q) b(X_q, t) dV_q.
void TetProblem::begin_step(double time, double dt) {
  if (!std::isfinite(time) || !std::isfinite(dt) || dt < 0.0) {
    throw std::invalid_argument("TetProblem::begin_step: time and dt must be finite, dt >= 0");
  }
  time_ = time;
  dt_ = dt;
  trial_valid_ = false;
  bases_.begin_step();  // the first iterate starts from the committed p~, J~
  const TetMesh& mesh = space_.mesh();
  prescribed_.setZero(3 * mesh.num_nodes());
  for (const TetDirichlet& c : conditions_) {
    for (int n : c.nodes) {
      const Eigen::Vector3d v = c.value ? c.value(mesh.nodes[n], time_) : Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        if (c.components[k]) {
          prescribed_[3 * n + k] = v[k];
        }
      }
    }
  }
  f_ext_.setZero(3 * mesh.num_nodes());
  if (body_force_) {
    const int nen = space_.nodes_per_element();
    for (int e = 0; e < mesh.num_elements(); ++e) {
      const auto el = mesh.element(e);
      for (int q = 0; q < space_.points_per_element(); ++q) {
        const Eigen::Vector3d b = body_force_(space_.position(e, q), time_) * space_.dv(e)[q];
        const auto N = space_.values(q);
        for (int a = 0; a < nen; ++a) {
          f_ext_.segment<3>(3 * el[a]) += N[a] * b;
        }
      }
    }
  }
  add_surface_loads(mesh, surface_loads_, time_, f_ext_);
}

Eigen::VectorXd TetProblem::full_displacement(const Eigen::VectorXd& u) const {
  Eigen::VectorXd full = prescribed_;
  for (int d = 0; d < full.size(); ++d) {
    if (free_index_[d] >= 0) {
      full[d] = u[free_index_[d]];
    }
  }
  return full;
}

std::string TetProblem::describe_failure(int e, const KernelStatus& s) const {
  std::ostringstream msg;
  msg << "tetrahedron " << e << " (region " << space_.mesh().element_region[e] << ")";
  if (s.point >= 0) {
    const Eigen::Vector3d& X = space_.position(e, s.point);
    msg << ", quadrature point " << s.point << " at X = (" << X[0] << ", " << X[1] << ", " << X[2]
        << ") m";
  }
  msg << ", t = " << time_ << " s: " << continuum::describe_kernel_status(s, law_.name());
  return msg.str();
}

// The element's data as a continuum::ElementView; the mixed kernel also gets phi at the points
// and M_e (tet_problem.hpp), the displacement kernel F S only (continuum/element_kernels.hpp).
KernelStatus TetProblem::element_kernel(int e, const MaterialContext& ctx, bool tangent,
                                        ElementWorkspace& ws,
                                        const continuum::MixedBase* base) const {
  ElementView view;
  view.nen = space_.nodes_per_element();
  view.nqp = space_.points_per_element();
  view.gradients = space_.gradients(e, 0);
  view.dv = space_.dv(e);
  if (formulation_ != Formulation::mixed) {
    return continuum::displacement_kernel(view, ctx, tangent, ws);
  }
  view.pressure_size = pressure_size_;
  view.pressure = pressure_values_.data() + static_cast<std::size_t>(e) * view.nqp * pressure_size_;
  return continuum::mixed_kernel(view, ctx, mass_[e], mass_matrix_[e], base, tangent, ws);
}

// Element loop: kernel per element into the thread's workspace, scatter by colour (DESIGN 2, 5).
solver::EvaluationStatus TetProblem::assemble(const Eigen::VectorXd& u_full, bool want_tangent,
                                              double* values, bool use_base, bool trial_is_current,
                                              const Eigen::VectorXd* increment,
                                              Eigen::VectorXd* K_increment) {
  f_int_.setZero(u_full.size());
  if (K_increment != nullptr)
    K_increment->setZero(u_full.size());
  const bool mixed = formulation_ == Formulation::mixed;
  const continuum::MixedBases::Pass pass = bases_.begin_pass(use_base, want_tangent);
  const int nqp = space_.points_per_element();
  const int nen = space_.nodes_per_element();
  const std::size_t hs = static_cast<std::size_t>(history_size_);
  thread_J_range_.assign(workspaces_.size(), continuum::JacobianRange{});
  auto body = [&](int e, int thread) -> solver::EvaluationStatus {
    ElementWorkspace& ws = workspaces_[thread];
    const auto el = space_.mesh().element(e);
    for (int a = 0; a < nen; ++a) {
      ws.ue.col(a) = u_full.segment<3>(3 * el[a]);
    }
    MaterialContext ctx = continuum::element_material_context(
        law_, fibres_, e, nqp, time_, dt_, history_committed_,
        history_trial_.data() + static_cast<std::size_t>(e) * nqp * hs);
    ctx.trial_is_current = trial_is_current;
    continuum::MixedBase base_view;
    const KernelStatus ks = element_kernel(
        e, ctx, want_tangent, ws, mixed ? bases_.element_base(pass, e, ws, base_view) : nullptr);
    if (!ks.ok()) {
      return solver::EvaluationStatus::failure(describe_failure(e, ks));
    }
    thread_J_range_[thread].take_element(e, std::span<const double>(ws.J.data(), nqp));
    if (mixed)
      bases_.store(pass, e, ws);
    const auto& dofs = element_dofs_[e];
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      f_int_[dofs[i]] += ws.fe[static_cast<Eigen::Index>(i)];
    }
    if (want_tangent) {
      pattern_.add_element_matrix(e, ws.ke, values);
      if (increment != nullptr) {
        for (std::size_t j = 0; j < dofs.size(); ++j) {
          const double d = (*increment)[dofs[j]];
          if (d != 0.0)
            for (std::size_t i = 0; i < dofs.size(); ++i)
              (*K_increment)[dofs[i]] +=
                  ws.ke(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) * d;
        }
      }
    }
    return solver::EvaluationStatus::success();
  };
  const solver::EvaluationStatus status =
      solver::for_each_element_coloured(colouring_, options_.threads, body);
  if (mixed)
    bases_.end_pass(pass, status.ok);
  return status;
}

// r = f_int(u) - f_ext(t) on the free DOFs, K = dr/du (NonlinearProblem::evaluate).
solver::EvaluationStatus TetProblem::evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                                              solver::SparseMatrix* tangent) {
  if (u.size() != size()) {
    throw std::invalid_argument("TetProblem::evaluate: vector of size " + std::to_string(u.size()) +
                                ", expected " + std::to_string(size()));
  }
  // Newton's tangent pass comes at the state its line search has just evaluated (iga::Problem).
  const bool trial_is_current = trial_is_at(u);
  trial_valid_ = false;
  u_full_ = full_displacement(u);
  double* values = nullptr;
  if (tangent != nullptr) {
    if (!pattern_.matches(*tangent)) {
      *tangent = pattern_.make_matrix();
    } else {
      std::fill(tangent->valuePtr(), tangent->valuePtr() + tangent->nonZeros(), 0.0);
    }
    values = tangent->valuePtr();
  }
  const solver::EvaluationStatus status =
      assemble(u_full_, tangent != nullptr, values, true, trial_is_current);
  if (!status.ok) {
    return status;
  }
  evaluated_J_range_ = continuum::JacobianRange::of(thread_J_range_);
  residual.resize(num_free_);
  for (int d = 0; d < f_int_.size(); ++d) {
    if (free_index_[d] >= 0) {
      residual[free_index_[d]] = f_int_[d] - f_ext_[d];
    }
  }
  if (!residual.allFinite()) {
    return solver::EvaluationStatus::failure(
        "TetProblem: non-finite residual at t = " + std::to_string(time_) + " s");
  }
  last_u_ = u;
  trial_valid_ = true;
  return solver::EvaluationStatus::success();
}

bool TetProblem::trial_is_at(const Eigen::VectorXd& u) const {
  return trial_valid_ && last_u_.size() == u.size() && last_u_ == u;
}

// Makes the trial history at u the committed one (re-evaluating when the last evaluation was
// elsewhere).
void TetProblem::commit_step(const Eigen::VectorXd& u) {
  if (!trial_is_at(u)) {
    Eigen::VectorXd r;
    const solver::EvaluationStatus status = evaluate(u, r, nullptr);
    if (!status.ok) {
      throw std::runtime_error("TetProblem::commit_step: the state to commit does not evaluate: " +
                               status.message);
    }
  }
  history_previous_.swap(history_committed_);
  history_committed_ = history_trial_;
  committed_J_range_ = evaluated_J_range_;
  if (formulation_ == Formulation::mixed)
    bases_.commit();
  committed_full_ = full_displacement(u);
  committed_time_ = time_;
  committed_dt_ = dt_;
}

// K_ff du_f = -(f_int(u_n) + K_fp du_p - f_ext(t_n+1))_f at the committed state (header).
solver::EvaluationStatus TetProblem::predict(Eigen::VectorXd& u) {
  if (u.size() != size()) {
    throw std::invalid_argument("TetProblem::predict: vector of size " + std::to_string(u.size()) +
                                ", expected " + std::to_string(size()));
  }
  if (size() == 0)
    return solver::EvaluationStatus::success();
  Eigen::VectorXd old_full = committed_full_;
  for (int d = 0; d < old_full.size(); ++d)
    if (free_index_[d] >= 0)
      old_full[d] = u[free_index_[d]];
  const Eigen::VectorXd increment = full_displacement(u) - old_full;  // zero on free DOFs
  if (increment.lpNorm<Eigen::Infinity>() == 0.0)
    return solver::EvaluationStatus::success();  // nothing prescribed moves: Newton predicts
  solver::SparseMatrix& matrix = predictor_.zeroed_matrix(pattern_);
  Eigen::VectorXd K_increment;
  trial_valid_ = false;
  // A tangent pass at the committed state with the exact projection: Newton's first iterate is
  // linearised about its base (after a failure, about the committed one, anchored).
  const solver::EvaluationStatus status =
      assemble(old_full, true, matrix.valuePtr(), false, false, &increment, &K_increment);
  if (!status.ok) {
    return solver::EvaluationStatus::failure("predictor: " + status.message);
  }
  Eigen::VectorXd rhs(num_free_);
  for (int d = 0; d < f_int_.size(); ++d)
    if (free_index_[d] >= 0)
      rhs[free_index_[d]] = -(f_int_[d] + K_increment[d] - f_ext_[d]);
  Eigen::VectorXd du;
  const solver::EvaluationStatus solved = predictor_.solve(options_.storage, rhs, du);
  if (!solved.ok) {
    return solved;
  }
  u += du;
  return solver::EvaluationStatus::success();
}

solver::EvaluationStatus TetProblem::internal_force(const Eigen::VectorXd& u,
                                                    Eigen::VectorXd& f_int) {
  if (u.size() != size()) {
    throw std::invalid_argument("TetProblem::internal_force: vector of size " +
                                std::to_string(u.size()) + ", expected " + std::to_string(size()));
  }
  // The reaction probes ask at the converged state, which Newton has just evaluated.
  const bool trial_is_current = trial_is_at(u);
  trial_valid_ = false;
  u_full_ = full_displacement(u);
  const solver::EvaluationStatus status =
      assemble(u_full_, false, nullptr, false, trial_is_current);
  if (status.ok) {
    f_int = f_int_;
    last_u_ = u;
    trial_valid_ = true;
  }
  return status;
}

Eigen::Vector3d TetProblem::sum_over_nodes(const Eigen::VectorXd& f_full,
                                           std::span<const int> nodes) const {
  if (f_full.size() != 3 * space_.mesh().num_nodes()) {
    throw std::invalid_argument("sum_over_nodes: vector of size " + std::to_string(f_full.size()) +
                                ", expected " + std::to_string(3 * space_.mesh().num_nodes()));
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int n : nodes) {
    if (n < 0 || n >= space_.mesh().num_nodes()) {
      throw std::invalid_argument("sum_over_nodes: node " + std::to_string(n) + " out of range");
    }
    sum += f_full.segment<3>(3 * n);
  }
  return sum;
}

std::span<const double> TetProblem::committed_history(int element, int point) const {
  const std::size_t i = static_cast<std::size_t>(element) * space_.points_per_element() + point;
  return {history_committed_.data() + i * history_size_, static_cast<std::size_t>(history_size_)};
}

std::vector<Eigen::Matrix3d> TetProblem::deformation_gradients(
    const Eigen::VectorXd& u_full) const {
  std::vector<Eigen::Matrix3d> out;
  out.reserve(space_.num_points());
  const int nen = space_.nodes_per_element();
  for (int e = 0; e < space_.num_elements(); ++e) {
    const auto el = space_.mesh().element(e);
    for (int q = 0; q < space_.points_per_element(); ++q) {
      Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
      const Eigen::Vector3d* g = space_.gradients(e, q);
      for (int a = 0; a < nen; ++a) {
        F.noalias() += u_full.segment<3>(3 * el[a]) * g[a].transpose();
      }
      out.push_back(F);
    }
  }
  return out;
}

double TetProblem::current_volume(const Eigen::VectorXd& u_full) const {
  const std::vector<Eigen::Matrix3d> F = deformation_gradients(u_full);
  double v = 0.0;
  for (int e = 0; e < space_.num_elements(); ++e) {
    for (int q = 0; q < space_.points_per_element(); ++q) {
      v += F[static_cast<std::size_t>(e) * space_.points_per_element() + q].determinant() *
           space_.dv(e)[q];
    }
  }
  return v;
}

std::vector<continuum::PointEllipticity> TetProblem::committed_ellipticity(int normals) const {
  return continuum::ellipticity_at_points(law_, deformation_gradients(committed_full_), fibres_,
                                          history_previous_, committed_time_, committed_dt_,
                                          normals, options_.threads);
}

continuum::SteppedResponse TetProblem::committed_response(int e, int q) const {
  const TetPointState st = state_at_point(e, q);
  const std::size_t i =
      static_cast<std::size_t>(e) * space_.points_per_element() + static_cast<std::size_t>(q);
  const std::size_t hs = static_cast<std::size_t>(history_size_);
  return continuum::stepped_response(law_, st.F, fibres_[i],
                                     std::span<const double>(history_previous_.data() + i * hs, hs),
                                     committed_time_, committed_dt_, st.p_bar);
}

Eigen::VectorXd TetProblem::lumped_volumes() const {
  const TetMesh& mesh = space_.mesh();
  const int nen = space_.nodes_per_element();
  Eigen::VectorXd volumes = Eigen::VectorXd::Zero(mesh.num_nodes());
  Eigen::VectorXd diagonal(nen);
  for (int e = 0; e < space_.num_elements(); ++e) {
    diagonal.setZero();
    double element_volume = 0.0;
    for (int q = 0; q < space_.points_per_element(); ++q) {
      const auto N = space_.values(q);
      const double dv = space_.dv(e)[q];
      element_volume += dv;
      for (int a = 0; a < nen; ++a)
        diagonal[a] += N[a] * N[a] * dv;
    }
    const auto nodes = mesh.element(e);
    const double scale = element_volume / diagonal.sum();
    for (int a = 0; a < nen; ++a)
      volumes[nodes[a]] += diagonal[a] * scale;
  }
  return volumes;
}

}  // namespace isomuscle::tet
