#include "continuum/element_workspace.hpp"

#include <sstream>
#include <stdexcept>

#include "continuum/point_contributions.hpp"

namespace isomuscle::continuum {

// Offsets e nqp (fibres) and e nqp history_size (committed history) into element-major arrays.
MaterialContext element_material_context(const materials::MaterialLaw& law,
                                         const std::vector<Eigen::Vector3d>& fibres, int e, int nqp,
                                         double time, double dt,
                                         const std::vector<double>& history_committed,
                                         double* history_trial) {
  const std::size_t points = static_cast<std::size_t>(e) * static_cast<std::size_t>(nqp);
  const std::size_t hs = static_cast<std::size_t>(law.history_size());
  MaterialContext ctx;
  ctx.law = &law;
  ctx.fibres = fibres.data() + points;
  ctx.time = time;
  ctx.dt = dt;
  if (hs > 0) {
    ctx.history_committed = history_committed.data() + points * hs;
    ctx.history_trial = history_trial;
  }
  return ctx;
}

UniformMaterialContext::UniformMaterialContext(const materials::MaterialLaw& law,
                                               const Eigen::Vector3d& fibre,
                                               const std::vector<double>& history, double time,
                                               double dt, int nqp)
    : fibres_(static_cast<std::size_t>(nqp), fibre) {
  const std::size_t hs = static_cast<std::size_t>(law.history_size());
  if (history.size() != hs)
    throw std::invalid_argument("uniform material state: " + std::to_string(history.size()) +
                                " history values, the law '" + law.name() + "' has " +
                                std::to_string(hs));
  for (int q = 0; q < nqp; ++q)
    committed_.insert(committed_.end(), history.begin(), history.end());
  trial_.resize(committed_.size());
  context_ = element_material_context(law, fibres_, 0, nqp, time, dt, committed_, trial_.data());
}

// The failure itself, in words (no equation; J = det F, J~ the projected dilatation).
std::string describe_kernel_status(const KernelStatus& s, std::string_view law_name) {
  std::ostringstream msg;
  switch (s.kind) {
    case KernelStatus::Kind::inverted:
      msg << "J = det F = " << s.value << " <= 0 (inverted)";
      break;
    case KernelStatus::Kind::inverted_dilatation:
      msg << "projected dilatation J~ = " << s.value << " <= 0";
      break;
    case KernelStatus::Kind::material:
      msg << "material law '" << law_name << "' failed (" << materials::to_string(s.material)
          << ") at J = " << s.value;
      break;
    case KernelStatus::Kind::not_finite:
      msg << "non-finite stress or tangent from law '" << law_name << "' at J = " << s.value;
      break;
    case KernelStatus::Kind::ok:
      msg << "ok";
      break;
  }
  return msg.str();
}

ElementWorkspace::ElementWorkspace(int nen, int nqp, int pressure_size) {
  const int n = 3 * nen;
  ue.setZero(3, nen);
  fe.setZero(n);
  ke.setZero(n, n);
  F.assign(nqp, Eigen::Matrix3d::Identity());
  S.assign(nqp, Eigen::Matrix3d::Zero());
  J.assign(nqp, 1.0);
  J_bar.assign(nqp, 1.0);
  p_bar.assign(nqp, 0.0);
  B.setZero(6, n);
  B_points.setZero(6 * kPointsPerProduct, n);
  CB_points.setZero(6 * kPointsPerProduct, n);
  grad_points.setZero(3 * kPointsPerProduct, nen);
  SG_points.setZero(3 * kPointsPerProduct, nen);
  dJ.setZero(3, nen);
  H.setZero(nen, nen);
  const int m = pressure_size;
  G.setZero(m, n);
  K_JJ.setZero(m, m);
  X.setZero(m, m);
  A.setZero(m, m);
  AG.setZero(m, n);
  theta.setZero(m);
  pi.setZero(m);
  rhs.setZero(m);
  R_pi.setZero(m);
  R_theta.setZero(m);
}

}  // namespace isomuscle::continuum
