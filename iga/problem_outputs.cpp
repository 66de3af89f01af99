// Output queries of iga::Problem: volume, point values, stresses, tessellation (problem.hpp).
#include <Eigen/LU>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "iga/problem.hpp"
#include "iga/quadrature_point_interpolation.hpp"

namespace isomuscle::iga {

// F = I + sum_a u_a (x) grad R_a at every quadrature point, element-major.
std::vector<Eigen::Matrix3d> Problem::deformation_gradients(const Eigen::VectorXd& u_full) const {
  if (u_full.size() != dofs_.num_dofs()) {
    throw std::invalid_argument("deformation_gradients: vector of size " +
                                std::to_string(u_full.size()) + ", expected " +
                                std::to_string(dofs_.num_dofs()));
  }
  const int nqp = space_.points_per_element();
  std::vector<Eigen::Matrix3d> F(static_cast<std::size_t>(space_.num_elements()) * nqp,
                                 Eigen::Matrix3d::Identity());
  for (int e = 0; e < space_.num_elements(); ++e) {
    const auto cps = space_.control_points(e);
    for (int q = 0; q < nqp; ++q) {
      const auto grad = space_.gradients(e, q);
      Eigen::Matrix3d& Fq = F[static_cast<std::size_t>(e) * nqp + q];
      for (std::size_t a = 0; a < cps.size(); ++a)
        Fq.noalias() += u_full.segment<3>(3 * dofs_.node(cps[a])) * grad[a].transpose();
    }
  }
  return F;
}

// V = int J dV over the reference configuration (J = det F at every quadrature point), m^3.
double Problem::current_volume(const Eigen::VectorXd& u_full) const {
  const std::vector<Eigen::Matrix3d> F = deformation_gradients(u_full);
  const int nqp = space_.points_per_element();
  double volume = 0.0;
  for (int e = 0; e < space_.num_elements(); ++e) {
    for (int q = 0; q < nqp; ++q)
      volume += F[static_cast<std::size_t>(e) * nqp + q].determinant() * space_.dv(e, q);
  }
  return volume;
}

std::vector<continuum::PointEllipticity> Problem::committed_ellipticity(int normals) const {
  return continuum::ellipticity_at_points(law_, deformation_gradients(committed_full_), fibres_,
                                          history_previous_, committed_time_, committed_dt_,
                                          normals, options_.threads);
}

std::span<const double> Problem::history_before_step(int e, int q) const {
  const std::size_t hs = static_cast<std::size_t>(history_size_);
  const std::size_t i =
      static_cast<std::size_t>(e) * space_.points_per_element() + static_cast<std::size_t>(q);
  return std::span<const double>(history_previous_.data() + i * hs, hs);
}

continuum::SteppedResponse Problem::committed_response(int e, int q) const {
  const PointState st = state_at_point(e, q);
  return continuum::stepped_response(law_, st.field.F, st.fibre, history_before_step(e, q),
                                     committed_time_, committed_dt_, st.p_bar);
}

LayerState Problem::committed_layer_state(int e, int q) const {
  const PointState st = state_at_point(e, q);
  const std::span<const double> history = history_before_step(e, q);
  LayerState out;
  out.law = &law_;
  out.F = std::cbrt(st.J_bar / st.field.F.determinant()) * st.field.F;
  out.fibre = st.fibre;
  out.history.assign(history.begin(), history.end());
  out.time = committed_time_;
  out.dt = committed_dt_;
  return out;
}

Eigen::VectorXd Problem::lumped_volumes() const {
  Eigen::VectorXd volumes = Eigen::VectorXd::Zero(dofs_.num_nodes());
  for (int e = 0; e < space_.num_elements(); ++e) {
    const auto cps = space_.control_points(e);
    for (int q = 0; q < space_.points_per_element(); ++q) {
      const auto values = space_.values(e, q);
      for (std::size_t a = 0; a < cps.size(); ++a)
        volumes[dofs_.node(cps[a])] += values[a] * space_.dv(e, q);
    }
  }
  return volumes;
}

Eigen::Vector3d Problem::displacement_at(const Eigen::VectorXd& u_full,
                                         const Eigen::Vector3d& xi) const {
  return evaluate_field(space_, dofs_, u_full, xi).u;
}

Tessellation Problem::tessellate(const Eigen::VectorXd& u_full, int subdivisions) const {
  return iga::tessellate(space_, dofs_, u_full, subdivisions);
}

PointState Problem::state_at(const Eigen::Vector3d& xi) const {
  const int e = space_.locate(xi);
  const std::vector<PointState> states = element_states(e);
  return interpolate_state(e, states, xi);
}

PointState Problem::state_at_point(int e, int q) const {
  if (e < 0 || e >= space_.num_elements() || q < 0 || q >= space_.points_per_element()) {
    throw std::invalid_argument("state_at_point: element " + std::to_string(e) + " or point " +
                                std::to_string(q) + " out of range");
  }
  return element_states(e)[static_cast<std::size_t>(q)];
}

// The converged sigma, J~, p~ and reference fibre N interpolated from the quadrature points
// (quadrature_point_interpolation.hpp: never the law at F(xi) with a neighbour's history), with the
// exact u(xi), F(xi); S = J F^-1 sigma F^-T (thesis 5.41), a = F N / |F N| (thesis 5.30) at xi.
// Interpolating sigma (not S) keeps the law's Cauchy parts, interpolated alike by the stress
// probes, summing to the total.
PointState Problem::interpolate_state(int e, std::span<const PointState> states,
                                      const Eigen::Vector3d& xi) const {
  if (states.size() != static_cast<std::size_t>(space_.points_per_element())) {
    throw std::invalid_argument("interpolate_state: " + std::to_string(states.size()) +
                                " states, expected one per quadrature point");
  }
  const std::vector<double> w = quadrature_point_weights(space_, e, xi);
  PointState st;
  st.field = evaluate_field(space_, dofs_, committed_full_, xi);
  if (!st.field.regular) {
    std::ostringstream msg;
    msg << "state at xi = (" << xi[0] << ", " << xi[1] << ", " << xi[2]
        << "): the parametrisation is singular there (collapsed axis), F is undefined; evaluate "
           "at a point off the axis";
    throw std::invalid_argument(msg.str());
  }
  const Eigen::Matrix3d& F = st.field.F;
  st.J = F.determinant();
  if (!(st.J > 0.0)) {
    std::ostringstream msg;
    msg << "state at xi = (" << xi[0] << ", " << xi[1] << ", " << xi[2] << "): J = " << st.J
        << " <= 0";
    throw std::runtime_error(msg.str());
  }
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  st.J_bar = 0.0;
  st.p_bar = 0.0;
  Eigen::Vector3d N = Eigen::Vector3d::Zero();
  for (std::size_t q = 0; q < w.size(); ++q) {
    sigma += w[q] * states[q].cauchy;
    st.J_bar += w[q] * states[q].J_bar;
    st.p_bar += w[q] * states[q].p_bar;
    N += w[q] * states[q].fibre;
  }
  if (formulation_ != Formulation::mixed)
    st.J_bar = st.J;
  st.fibre = N.normalized();
  const Eigen::Matrix3d F_inv = F.inverse();
  st.S = st.J * F_inv * sigma * F_inv.transpose();
  continuum::complete_point_stress(F, st);
  return st;
}

void Problem::committed_element_pass(int e, ElementWorkspace& ws, bool want_tangent) const {
  const int nqp = space_.points_per_element();
  const std::size_t hs = static_cast<std::size_t>(history_size_);
  const auto cps = space_.control_points(e);
  for (std::size_t a = 0; a < cps.size(); ++a) {
    ws.ue.col(static_cast<Eigen::Index>(a)) = committed_full_.segment<3>(3 * dofs_.node(cps[a]));
  }
  std::vector<double> scratch(static_cast<std::size_t>(nqp) * hs);
  const MaterialContext ctx = continuum::element_material_context(
      law_, fibres_, e, nqp, committed_time_, committed_dt_, history_previous_, scratch.data());
  const ElementView view = element_view(space_, e);
  const KernelStatus ks = formulation_ == Formulation::mixed
                              ? mixed_kernel(view, ctx, pressure_, e, nullptr, want_tangent, ws)
                              : displacement_kernel(view, ctx, want_tangent, ws);
  if (!ks.ok()) {
    throw std::runtime_error("committed state: " + describe_failure(e, ks));
  }
}

Eigen::MatrixXd Problem::committed_element_tangent(int e, const LayerState* homogeneous) const {
  if (e < 0 || e >= space_.num_elements()) {
    throw std::invalid_argument("committed_element_tangent: element " + std::to_string(e) +
                                " out of range");
  }
  const int nqp = space_.points_per_element();
  const bool mixed = formulation_ == Formulation::mixed;
  ElementWorkspace ws(space_.functions_per_element(), nqp, mixed ? pressure_.size() : 1);
  if (homogeneous == nullptr) {
    committed_element_pass(e, ws, true);
    return ws.ke;
  }
  const continuum::UniformMaterialContext material(law_, homogeneous->fibre, homogeneous->history,
                                                   homogeneous->time, homogeneous->dt, nqp);
  const Eigen::Matrix3d gradient = homogeneous->F - Eigen::Matrix3d::Identity();
  const auto cps = space_.control_points(e);
  for (std::size_t a = 0; a < cps.size(); ++a) {
    ws.ue.col(static_cast<Eigen::Index>(a)) =
        gradient * space_.volume().points()[static_cast<std::size_t>(cps[a])];
  }
  const ElementView view = element_view(space_, e);
  const MaterialContext& ctx = material.context();
  const KernelStatus ks = mixed ? mixed_kernel(view, ctx, pressure_, e, nullptr, true, ws)
                                : displacement_kernel(view, ctx, true, ws);
  if (!ks.ok()) {
    throw std::runtime_error("homogeneous state on the element's geometry: " +
                             describe_failure(e, ks));
  }
  return ws.ke;
}

// States at the quadrature points from one kernel pass: F, S, J (and J~, p~) as assembled.
std::vector<PointState> Problem::element_states(int e) const {
  if (e < 0 || e >= space_.num_elements()) {
    throw std::invalid_argument("element_states: element " + std::to_string(e) + " out of range");
  }
  const int nqp = space_.points_per_element();
  const bool mixed = formulation_ == Formulation::mixed;
  ElementWorkspace ws(space_.functions_per_element(), nqp, mixed ? pressure_.size() : 1);
  committed_element_pass(e, ws);
  std::vector<PointState> out(nqp);
  const auto cps = space_.control_points(e);
  for (int q = 0; q < nqp; ++q) {
    PointState& st = out[q];
    st.field.element = e;
    st.field.xi = space_.parametric(e, q);
    st.field.X = space_.position(e, q);
    st.field.jacobian = space_.jacobian(e, q);
    const auto R = space_.values(e, q);
    st.field.u.setZero();
    for (std::size_t a = 0; a < cps.size(); ++a) {
      st.field.u += R[a] * ws.ue.col(static_cast<Eigen::Index>(a));
    }
    st.field.F = ws.F[q];
    continuum::point_stress_from_kernel(ws, q, mixed,
                                        fibres_[static_cast<std::size_t>(e) * nqp + q], st);
  }
  return out;
}

}  // namespace isomuscle::iga
