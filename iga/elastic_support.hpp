#pragma once
// Elastic (Winkler) supports: a parametric side held by distributed springs, a nominal traction
// t0 = -k P u per unit reference area, k the stiffness (Pa/m) and P the projection onto the
// supported components x, y, z. It stands for the tissue a muscle is attached through (a tendon,
// aponeurosis or periosteum of finite compliance) where a clamp would make the side's edges
// singular: the body meets the clamp at a right angle with the stress unbounded there, and no mesh
// converges the fields next to it (validation/suite/README.md, the DAO's y). The springs are
// linear and act in the reference configuration, like the dead loads (loads.hpp), so their
// stiffness is the constant matrix
//   K_ab = k P int_side R_a R_b dA,
// per element of the side in the element's own DOF order (3 a + c): the residual gets K u and the
// tangent K. Their force on the body is -K u; the reactions of the problem's internal force leave
// the springs out, so that the internal force at the supported control points is that force.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "iga/boundary_conditions.hpp"
#include "iga/space.hpp"

namespace isomuscle::iga {

struct ElasticSupport {
  std::string label;  // for messages
  Side side = Side::u0;
  double stiffness = 0.0;                            // k, Pa/m (traction per metre)
  std::array<bool, 3> components{true, true, true};  // x, y, z held by springs
};

// One element's spring matrix: n_e x n_e with n_e = 3 functions_per_element().
struct SupportElementMatrix {
  int element = 0;
  Eigen::MatrixXd matrix;
};

// The spring matrices of all supports, one per element that has a face on a supported side (two
// supports on one element's faces are summed into one matrix). Throws std::invalid_argument naming
// the support when its stiffness is not finite and positive, it holds no component, or its side
// has no area (the collapsed centreline).
std::vector<SupportElementMatrix> support_element_matrices(
    const Space& space, const std::vector<ElasticSupport>& supports);

}  // namespace isomuscle::iga
