#pragma once
// The stress and fibre outputs at one material point of the committed state, shared by the
// discretisations' output structs (iga::PointState, tet::TetPointState derive from it).
#include <Eigen/Core>

#include "continuum/element_workspace.hpp"

namespace isomuscle::continuum {

struct PointStress {
  double J = 1.0;                                    // det F
  double J_bar = 1.0;                                // J~ (mixed formulation), else J
  double p_bar = 0.0;                                // p~ (mixed formulation), else 0, Pa
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();       // second Piola–Kirchhoff, Pa
  Eigen::Matrix3d cauchy = Eigen::Matrix3d::Zero();  // sigma = F S F^T / J (thesis 5.41), Pa
  Eigen::Vector3d fibre = Eigen::Vector3d::UnitZ();  // reference N
  Eigen::Vector3d fibre_deformed = Eigen::Vector3d::UnitZ();  // a = F N / |F N| (thesis 5.30)
  double fibre_stretch = 1.0;                                 // |F N|
};

// From st.J, st.S and st.fibre: sigma = F S F^T / J (thesis 5.41), lambda_f = |F N| and
// a = F N / lambda_f (thesis 5.30). Throws std::runtime_error when |F N| is not positive.
void complete_point_stress(const Eigen::Matrix3d& F, PointStress& st);

// Point q of a kernel pass (ws): J, S and, when mixed, J~ and p~ (else J~ = J, p~ = 0), then
// complete_point_stress with the reference fibre N.
void point_stress_from_kernel(const ElementWorkspace& ws, int q, bool mixed,
                              const Eigen::Vector3d& fibre, PointStress& st);

}  // namespace isomuscle::continuum
