#include "iga/problem.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "continuum/problem_setup.hpp"

namespace isomuscle::iga {

void ProblemOptions::validate() const {
  if (pressure_degree < 0 || pressure_degree > 4) {
    throw std::invalid_argument("pressure_degree " + std::to_string(pressure_degree) +
                                " outside the valid range 0..4 (0 = mean dilatation)");
  }
  if (threads < 0) {
    throw std::invalid_argument("threads " + std::to_string(threads) +
                                " must be >= 0 (0 = OpenMP default)");
  }
  if (!(mixed_threshold > 0.0)) {
    throw std::invalid_argument(
        "mixed_threshold (bulk / shear modulus above which 'automatic' "
        "chooses the mixed formulation) must be > 0");
  }
}

Problem::Problem(const Space& space, const DofMap& dofs, const materials::MaterialLaw& law,
                 std::vector<Eigen::Vector3d> fibres, const DirichletConditions& conditions,
                 Loads loads, ProblemOptions options)
    : space_(space),
      dofs_(dofs),
      law_(law),
      fibres_(std::move(fibres)),
      loads_(std::move(loads)),
      options_(options) {
  options_.validate();
  if (dofs_.num_control_points() != space_.volume().num_control_points()) {
    throw std::invalid_argument(
        "iga::Problem: the DofMap has " + std::to_string(dofs_.num_control_points()) +
        " control points, the space " + std::to_string(space_.volume().num_control_points()));
  }
  formulation_ =
      continuum::resolve_formulation(options_.formulation, law_, options_.mixed_threshold);
  continuum::check_unit_fibres(fibres_, space_.num_points(), "iga::Problem");
  constraints_ = ConstrainedDofs(dofs_, conditions);

  const int nel = space_.num_elements();
  const int nen = space_.functions_per_element();
  element_all_dofs_.resize(nel);
  std::vector<std::vector<int>> free_lists(nel);
  for (int e = 0; e < nel; ++e) {
    const auto cps = space_.control_points(e);
    auto& all = element_all_dofs_[e];
    all.resize(3 * nen);
    free_lists[e].resize(3 * nen);
    for (int a = 0; a < nen; ++a) {
      for (int k = 0; k < 3; ++k) {
        const int dof = DofMap::dof(dofs_.node(cps[a]), k);
        all[3 * a + k] = dof;
        free_lists[e][3 * a + k] = constraints_.free_index(dof);
      }
    }
  }
  pattern_ = solver::SparsityPattern(solver::ElementDofs(free_lists), constraints_.num_free(),
                                     options_.storage, options_.scatter);
  colouring_ = solver::ElementColouring(solver::ElementDofs(element_all_dofs_));
  if (formulation_ == Formulation::mixed) {
    pressure_ = PressureSpace(space_, options_.pressure_degree);
    bases_.resize(nel, pressure_.size(), 3 * nen);
  }
  set_threads(options_.threads);

  history_size_ = law_.history_size();
  const std::size_t nh = static_cast<std::size_t>(space_.num_points()) * history_size_;
  history_committed_.assign(nh, 0.0);
  if (history_size_ > 0) {
    for (int i = 0; i < space_.num_points(); ++i) {
      law_.initial_history(std::span<double>(
          history_committed_.data() + static_cast<std::size_t>(i) * history_size_, history_size_));
    }
  }
  history_trial_ = history_committed_;
  history_previous_ = history_committed_;
  committed_full_.setZero(dofs_.num_dofs());
  committed_free_.setZero(constraints_.num_free());
  u_full_.setZero(dofs_.num_dofs());
  f_int_.setZero(dofs_.num_dofs());
  begin_step(0.0, 0.0);
}

Problem::~Problem() = default;

void Problem::set_threads(int threads) {
  if (threads < 0) {
    throw std::invalid_argument("threads must be >= 0 (0 = OpenMP default)");
  }
  options_.threads = threads;
  const int n = solver::resolve_thread_count(threads);
  const int m = formulation_ == Formulation::mixed ? pressure_.size() : 1;
  workspaces_.assign(
      n, ElementWorkspace(space_.functions_per_element(), space_.points_per_element(), m));
}

// Prescribed values and dead loads at t = time (NonlinearProblem::begin_step).
void Problem::begin_step(double time, double dt) {
  if (!std::isfinite(time) || !std::isfinite(dt) || dt < 0.0) {
    throw std::invalid_argument("iga::Problem::begin_step: time and dt must be finite, dt >= 0");
  }
  time_ = time;
  dt_ = dt;
  trial_valid_ = false;
  bases_.begin_step();  // the first iterate starts from the committed p~, J~
  if (loads_.empty()) {
    f_ext_.setZero(dofs_.num_dofs());
  } else {
    assemble_external_forces(space_, dofs_, loads_, time_, f_ext_);
  }
}

std::string Problem::describe_failure(int e, const KernelStatus& s) const {
  const Element& el = space_.element(e);
  std::ostringstream msg;
  msg << "element " << e << " (knot spans " << el.span[0] << ", " << el.span[1] << ", "
      << el.span[2] << ")";
  if (s.point >= 0) {
    const Eigen::Vector3d& X = space_.position(e, s.point);
    const Eigen::Vector3d& xi = space_.parametric(e, s.point);
    msg << ", quadrature point " << s.point << " at X = (" << X[0] << ", " << X[1] << ", " << X[2]
        << "), xi = (" << xi[0] << ", " << xi[1] << ", " << xi[2] << ")";
  }
  msg << ", t = " << time_ << " s: " << continuum::describe_kernel_status(s, law_.name());
  return msg.str();
}

// Element loop: kernel per element (into the thread's workspace), scatter by colour (DESIGN 2, 5).
solver::EvaluationStatus Problem::assemble(const Eigen::VectorXd& u_full, bool want_tangent,
                                           double* tangent_values, bool use_base,
                                           bool trial_is_current, const Eigen::VectorXd* increment,
                                           Eigen::VectorXd* K_increment) {
  if (K_increment != nullptr) {
    K_increment->setZero(dofs_.num_dofs());
  }
  f_int_.setZero(dofs_.num_dofs());
  const int nqp = space_.points_per_element();
  const bool mixed = formulation_ == Formulation::mixed;
  const continuum::MixedBases::Pass pass = bases_.begin_pass(use_base, want_tangent);
  const std::size_t hs = static_cast<std::size_t>(history_size_);
  thread_J_range_.assign(workspaces_.size(), continuum::JacobianRange{});
  auto body = [&](int e, int thread) -> solver::EvaluationStatus {
    ElementWorkspace& ws = workspaces_[thread];
    const auto cps = space_.control_points(e);
    for (int a = 0; a < static_cast<int>(cps.size()); ++a) {
      ws.ue.col(a) = u_full.segment<3>(3 * dofs_.node(cps[a]));
    }
    MaterialContext ctx = continuum::element_material_context(
        law_, fibres_, e, nqp, time_, dt_, history_committed_,
        history_trial_.data() + static_cast<std::size_t>(e) * nqp * hs);
    ctx.trial_is_current = trial_is_current;
    const ElementView view = element_view(space_, e);
    MixedBase base_view;
    const KernelStatus ks =
        mixed ? mixed_kernel(view, ctx, pressure_, e, bases_.element_base(pass, e, ws, base_view),
                             want_tangent, ws)
              : displacement_kernel(view, ctx, want_tangent, ws);
    if (!ks.ok()) {
      return solver::EvaluationStatus::failure(describe_failure(e, ks));
    }
    thread_J_range_[thread].take_element(e, std::span<const double>(ws.J.data(), nqp));
    if (mixed)
      bases_.store(pass, e, ws);
    const auto& all = element_all_dofs_[e];
    for (std::size_t i = 0; i < all.size(); ++i) {
      f_int_[all[i]] += ws.fe[static_cast<Eigen::Index>(i)];
    }
    if (want_tangent) {
      pattern_.add_element_matrix(e, ws.ke, tangent_values);
      if (increment != nullptr) {
        for (std::size_t j = 0; j < all.size(); ++j) {
          const double d = (*increment)[all[j]];
          if (d != 0.0) {
            for (std::size_t i = 0; i < all.size(); ++i) {
              (*K_increment)[all[i]] +=
                  ws.ke(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) * d;
            }
          }
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
solver::EvaluationStatus Problem::evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& residual,
                                           solver::SparseMatrix* tangent) {
  if (u.size() != size()) {
    throw std::invalid_argument("iga::Problem::evaluate: vector of size " +
                                std::to_string(u.size()) + ", expected " + std::to_string(size()));
  }
  // Newton's tangent pass comes at the state its line search has just evaluated: the law's update
  // is then already in the trial history.
  const bool trial_is_current = trial_is_at(u);
  trial_valid_ = false;
  constraints_.expand(u, time_, u_full_);
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
  add_supports(u_full_, values);
  Eigen::VectorXd diff = f_int_ - f_ext_;
  constraints_.restrict_to_free(diff, residual);
  if (!residual.allFinite()) {
    return solver::EvaluationStatus::failure(
        "iga::Problem: non-finite residual at t = " + std::to_string(time_) + " s");
  }
  last_u_ = u;
  last_time_ = time_;
  trial_valid_ = true;
  return solver::EvaluationStatus::success();
}

void Problem::set_elastic_supports(const std::vector<ElasticSupport>& supports) {
  supports_ = support_element_matrices(space_, supports);
  support_settings_ = supports;
  trial_valid_ = false;
}

// f_int += K_e u_e, K += K_e, K_increment += K_e increment_e over the supported elements.
void Problem::add_supports(const Eigen::VectorXd& u_full, double* tangent_values,
                           const Eigen::VectorXd* increment, Eigen::VectorXd* K_increment) {
  Eigen::VectorXd ue, fe;
  for (const SupportElementMatrix& s : supports_) {
    const auto& all = element_all_dofs_[s.element];
    ue.resize(static_cast<Eigen::Index>(all.size()));
    for (std::size_t i = 0; i < all.size(); ++i)
      ue[static_cast<Eigen::Index>(i)] = u_full[all[i]];
    fe.noalias() = s.matrix * ue;
    for (std::size_t i = 0; i < all.size(); ++i)
      f_int_[all[i]] += fe[static_cast<Eigen::Index>(i)];
    if (tangent_values != nullptr)
      pattern_.add_element_matrix(s.element, s.matrix, tangent_values);
    if (increment != nullptr) {
      for (std::size_t i = 0; i < all.size(); ++i)
        ue[static_cast<Eigen::Index>(i)] = (*increment)[all[i]];
      fe.noalias() = s.matrix * ue;
      for (std::size_t i = 0; i < all.size(); ++i)
        (*K_increment)[all[i]] += fe[static_cast<Eigen::Index>(i)];
    }
  }
}

bool Problem::trial_is_at(const Eigen::VectorXd& u) const {
  return trial_valid_ && last_time_ == time_ && last_u_.size() == u.size() && last_u_ == u;
}

// Makes the trial history at u the committed one (re-evaluating when the last evaluation was
// elsewhere), and keeps the history it replaces for state_at().
void Problem::commit_step(const Eigen::VectorXd& u) {
  if (!trial_is_at(u)) {
    Eigen::VectorXd r;
    const solver::EvaluationStatus status = evaluate(u, r, nullptr);
    if (!status.ok) {
      throw std::runtime_error(
          "iga::Problem::commit_step: the state to commit does not evaluate: " + status.message);
    }
  }
  history_previous_.swap(history_committed_);
  history_committed_ = history_trial_;
  committed_J_range_ = evaluated_J_range_;
  if (formulation_ == Formulation::mixed)
    bases_.commit();
  constraints_.expand(u, time_, committed_full_);
  committed_free_ = u;
  committed_time_ = time_;
  committed_dt_ = dt_;
}

// K_ff du_f = -(f_int(u_n) + K_fp du_p - f_ext(t_n+1))_f at the committed state (header).
solver::EvaluationStatus Problem::predict(Eigen::VectorXd& u) {
  if (u.size() != size()) {
    throw std::invalid_argument("iga::Problem::predict: vector of size " +
                                std::to_string(u.size()) + ", expected " + std::to_string(size()));
  }
  if (size() == 0) {
    return solver::EvaluationStatus::success();
  }
  Eigen::VectorXd old_full;
  constraints_.expand(u, committed_time_, old_full);
  Eigen::VectorXd new_full;
  constraints_.expand(u, time_, new_full);
  const Eigen::VectorXd increment = new_full - old_full;  // zero on the free DOFs
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
  add_supports(old_full, matrix.valuePtr(), &increment, &K_increment);
  const Eigen::VectorXd full_rhs = f_int_ + K_increment - f_ext_;
  Eigen::VectorXd rhs;
  constraints_.restrict_to_free(full_rhs, rhs);
  Eigen::VectorXd du;
  const solver::EvaluationStatus solved = predictor_.solve(options_.storage, -rhs, du);
  if (!solved.ok) {
    return solved;
  }
  u += du;
  return solver::EvaluationStatus::success();
}

Eigen::VectorXd Problem::full_displacement(const Eigen::VectorXd& u) const {
  Eigen::VectorXd full;
  constraints_.expand(u, time_, full);
  return full;
}

std::span<const double> Problem::committed_history(int element, int point) const {
  const std::size_t i = static_cast<std::size_t>(element) * space_.points_per_element() +
                        static_cast<std::size_t>(point);
  return {history_committed_.data() + i * history_size_, static_cast<std::size_t>(history_size_)};
}

solver::EvaluationStatus Problem::internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& f_int) {
  if (u.size() != size()) {
    throw std::invalid_argument("iga::Problem::internal_force: vector of size " +
                                std::to_string(u.size()) + ", expected " + std::to_string(size()));
  }
  // The reaction probes ask at the converged state, which Newton has just evaluated.
  const bool trial_is_current = trial_is_at(u);
  trial_valid_ = false;
  constraints_.expand(u, time_, u_full_);
  const solver::EvaluationStatus status =
      assemble(u_full_, false, nullptr, false, trial_is_current);
  if (status.ok) {
    f_int = f_int_;
    last_u_ = u;
    last_time_ = time_;
    trial_valid_ = true;
  }
  return status;
}

Eigen::Vector3d Problem::sum_over_nodes(const Eigen::VectorXd& f_full,
                                        std::span<const int> nodes) const {
  if (f_full.size() != dofs_.num_dofs()) {
    throw std::invalid_argument("sum_over_nodes: vector of size " + std::to_string(f_full.size()) +
                                ", expected " + std::to_string(dofs_.num_dofs()));
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int n : nodes) {
    sum += f_full.segment<3>(3 * n);
  }
  return sum;
}

}  // namespace isomuscle::iga
