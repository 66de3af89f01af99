#include "continuum/point_state.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "materials/kinematics.hpp"

namespace isomuscle::continuum {

// sigma = F S F^T / J (thesis 5.41); lambda_f = |F N|, a = F N / lambda_f (thesis 5.30).
void complete_point_stress(const Eigen::Matrix3d& F, PointStress& st) {
  st.cauchy = materials::push_forward_stress(F, st.J, st.S);
  const Eigen::Vector3d FN = F * st.fibre;
  st.fibre_stretch = FN.norm();
  if (!(std::isfinite(st.fibre_stretch) && st.fibre_stretch > 0.0)) {
    std::ostringstream msg;
    msg << "deformed fibre direction undefined: |F N| = " << st.fibre_stretch
        << " (F is singular or not finite along the fibre; an inverted element?)";
    throw std::runtime_error(msg.str());
  }
  st.fibre_deformed = FN / st.fibre_stretch;
}

// The kernel's per-point results (element_kernels.hpp) as output state.
void point_stress_from_kernel(const ElementWorkspace& ws, int q, bool mixed,
                              const Eigen::Vector3d& fibre, PointStress& st) {
  const std::size_t i = static_cast<std::size_t>(q);
  st.J = ws.J[i];
  st.J_bar = mixed ? ws.J_bar[i] : ws.J[i];
  st.p_bar = mixed ? ws.p_bar[i] : 0.0;
  st.S = ws.S[i];
  st.fibre = fibre;
  complete_point_stress(ws.F[i], st);
}

}  // namespace isomuscle::continuum
