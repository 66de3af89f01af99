#include <sstream>
#include <stdexcept>

#include "geometry/fibre_field.hpp"
#include "materials/kinematics.hpp"
#include "tet/tet_problem.hpp"

namespace isomuscle::tet {

// S by the element kernel at the committed displacement with the pre-step history (mixed:
// S_iso + p~ J C^-1, tet_kernels.hpp); sigma = F S F^T / J (thesis 5.41); a = F N / |F N| and
// lambda_f = |F N| (thesis 5.30).
TetPointState TetProblem::state_at_point(int e, int q) const {
  const int nqp = space_.points_per_element();
  if (e < 0 || e >= space_.num_elements() || q < 0 || q >= nqp) {
    throw std::invalid_argument("state_at_point: element " + std::to_string(e) + " or point " +
                                std::to_string(q) + " out of range");
  }
  const int nen = space_.nodes_per_element();
  const bool mixed = formulation_ == TetFormulation::mixed;
  TetWorkspace ws(nen, nqp, pressure_size_);
  const auto el = space_.mesh().element(e);
  for (int a = 0; a < nen; ++a) {
    ws.ue.col(a) = committed_full_.segment<3>(3 * el[a]);
  }
  const std::size_t hs = static_cast<std::size_t>(history_size_);
  std::vector<double> scratch(static_cast<std::size_t>(nqp) * hs);
  TetMaterialContext ctx;
  ctx.law = &law_;
  ctx.fibres = fibres_.data() + static_cast<std::size_t>(e) * nqp;
  ctx.time = committed_time_;
  ctx.dt = committed_dt_;
  if (hs > 0) {
    ctx.history_committed = history_previous_.data() + static_cast<std::size_t>(e) * nqp * hs;
    ctx.history_trial = scratch.data();
  }
  TetElementView view;
  view.nen = nen;
  view.nqp = nqp;
  view.gradients = space_.gradients(e, 0);
  view.dv = space_.dv(e);
  TetKernelStatus ks;
  if (mixed) {
    view.pressure = pressure_values_.data() + static_cast<std::size_t>(e) * nqp * pressure_size_;
    ks = tet_mixed_kernel(view, ctx, pressure_size_, mass_[e], false, ws);
  } else {
    ks = tet_displacement_kernel(view, ctx, false, ws);
  }
  if (!ks.ok()) {
    throw std::runtime_error("state_at_point: " + describe_failure(e, ks));
  }
  TetPointState st;
  st.X = space_.position(e, q);
  const auto N = space_.values(q);
  for (int a = 0; a < nen; ++a) {
    st.displacement += N[a] * ws.ue.col(a);
  }
  st.F = ws.F[q];
  st.J = ws.J[q];
  st.J_bar = mixed ? ws.J_bar[q] : st.J;
  st.p_bar = mixed ? ws.p_bar[q] : 0.0;
  st.S = ws.S[q];
  st.cauchy = materials::push_forward_stress(st.F, st.J, st.S);
  st.fibre = fibres_[static_cast<std::size_t>(e) * nqp + q];
  st.fibre_stretch = geometry::fibre_stretch(st.F, st.fibre);
  st.fibre_deformed = geometry::deformed_fibre_direction(st.F, st.fibre);
  return st;
}

}  // namespace isomuscle::tet
