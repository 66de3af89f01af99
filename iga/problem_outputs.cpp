// Output queries of iga::Problem: volume, point values, stresses, tessellation (problem.hpp).
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "iga/problem.hpp"

namespace isomuscle::iga {

// V = int J dV over the reference configuration (J = det F at every quadrature point), m^3.
double Problem::current_volume(const Eigen::VectorXd& u_full) const {
  if (u_full.size() != dofs_.num_dofs()) {
    throw std::invalid_argument("current_volume: vector of size " + std::to_string(u_full.size()) +
                                ", expected " + std::to_string(dofs_.num_dofs()));
  }
  double volume = 0.0;
  for (int e = 0; e < space_.num_elements(); ++e) {
    const auto cps = space_.control_points(e);
    for (int q = 0; q < space_.points_per_element(); ++q) {
      const auto grad = space_.gradients(e, q);
      Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
      for (std::size_t a = 0; a < cps.size(); ++a) {
        F.noalias() += u_full.segment<3>(3 * dofs_.node(cps[a])) * grad[a].transpose();
      }
      volume += F.determinant() * space_.dv(e, q);
    }
  }
  return volume;
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
  const Element& el = space_.element(e);
  // Nearest quadrature point in the element's reference coordinates.
  const Eigen::Vector3d t = element_reference_coordinates(el, xi);
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int q = 0; q < space_.points_per_element(); ++q) {
    const double d = (element_reference_coordinates(el, space_.parametric(e, q)) - t).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = q;
    }
  }
  return evaluate_state(e, xi, best);
}

PointState Problem::state_at_point(int e, int q) const {
  if (e < 0 || e >= space_.num_elements() || q < 0 || q >= space_.points_per_element()) {
    throw std::invalid_argument("state_at_point: element " + std::to_string(e) + " or point " +
                                std::to_string(q) + " out of range");
  }
  return evaluate_state(e, space_.parametric(e, q), q);
}

// S from the law at F(xi) with the pre-step history of point qh (mixed: S_iso + p~ J C^-1 with the
// element's projections, element_kernels.hpp); sigma = F S F^T / J (thesis 5.41), a = F N / |F N|
// (thesis 5.30).
PointState Problem::evaluate_state(int e, const Eigen::Vector3d& xi, int qh) const {
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
  const int nqp = space_.points_per_element();
  const std::size_t hs = static_cast<std::size_t>(history_size_);
  const std::size_t point = static_cast<std::size_t>(e) * nqp + static_cast<std::size_t>(qh);
  st.fibre = fibres_[point];
  materials::PointInput in;
  in.F = F;
  in.fibre = st.fibre;
  in.time = committed_time_;
  in.dt = committed_dt_;
  std::vector<double> trial(hs);
  if (hs > 0) {
    in.history = std::span<const double>(history_previous_.data() + point * hs, hs);
  }
  materials::PointResult res;
  res.history = std::span<double>(trial.data(), hs);
  materials::PointStatus status;
  st.J_bar = st.J;
  if (formulation_ == Formulation::mixed) {
    ElementWorkspace ws(space_.functions_per_element(), nqp, pressure_.size());
    committed_element_pass(e, ws);
    std::vector<double> N(pressure_.size());
    pressure_.evaluate(element_reference_coordinates(space_.element(e), xi), N.data());
    const Eigen::Map<const Eigen::VectorXd> Nv(N.data(), pressure_.size());
    st.J_bar = Nv.dot(ws.theta);
    st.p_bar = Nv.dot(ws.pi);
    status = law_.evaluate_isochoric(in, res, false);
    const Eigen::Matrix3d F_inv = F.inverse();
    st.S = res.S + (st.p_bar * st.J) * (F_inv * F_inv.transpose());
  } else {
    status = law_.evaluate(in, res, false);
    st.S = res.S;
  }
  if (status != materials::PointStatus::ok || !st.S.allFinite()) {
    std::ostringstream msg;
    msg << "state at xi = (" << xi[0] << ", " << xi[1] << ", " << xi[2] << "): material law '"
        << law_.name() << "' failed (" << materials::to_string(status) << ")";
    throw std::runtime_error(msg.str());
  }
  continuum::complete_point_stress(F, st);
  return st;
}

void Problem::committed_element_pass(int e, ElementWorkspace& ws) const {
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
                              ? mixed_kernel(view, ctx, pressure_, e, nullptr, false, ws)
                              : displacement_kernel(view, ctx, false, ws);
  if (!ks.ok()) {
    throw std::runtime_error("committed state: " + describe_failure(e, ks));
  }
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
