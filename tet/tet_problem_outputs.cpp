#include <sstream>
#include <stdexcept>

#include "tet/tet_problem.hpp"

namespace isomuscle::tet {

// S by the element kernel at the committed displacement with the pre-step history (mixed:
// S_iso + p~ J C^-1, continuum/element_kernels.hpp); sigma = F S F^T / J (thesis 5.41); a = F N /
// |F N| and lambda_f = |F N| (thesis 5.30).
TetPointState TetProblem::state_at_point(int e, int q) const {
  const int nqp = space_.points_per_element();
  if (e < 0 || e >= space_.num_elements() || q < 0 || q >= nqp) {
    throw std::invalid_argument("state_at_point: element " + std::to_string(e) + " or point " +
                                std::to_string(q) + " out of range");
  }
  const int nen = space_.nodes_per_element();
  ElementWorkspace ws(nen, nqp, pressure_size_);
  const auto el = space_.mesh().element(e);
  for (int a = 0; a < nen; ++a) {
    ws.ue.col(a) = committed_full_.segment<3>(3 * el[a]);
  }
  const std::size_t hs = static_cast<std::size_t>(history_size_);
  std::vector<double> scratch(static_cast<std::size_t>(nqp) * hs);
  const MaterialContext ctx = continuum::element_material_context(
      law_, fibres_, e, nqp, committed_time_, committed_dt_, history_previous_, scratch.data());
  const KernelStatus ks = element_kernel(e, ctx, false, ws);
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
  continuum::point_stress_from_kernel(ws, q, formulation_ == Formulation::mixed,
                                      fibres_[static_cast<std::size_t>(e) * nqp + q], st);
  return st;
}

}  // namespace isomuscle::tet
