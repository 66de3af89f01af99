#pragma once
// Element kernels of the total Lagrangian formulation, independent of the discretisation (iga/
// knot-span elements, tet/ tetrahedra). A kernel reads one element's tabulated reference data
// (ElementView), its displacements and the committed material history, and writes the element
// internal force f_e (3 n_en), optionally the element tangent K_e = df_e/du_e (3 n_en x 3 n_en),
// and the trial history. Local DOF order: 3 a + i (function a, component i). No heap allocation:
// everything lives in an ElementWorkspace sized once per thread.
//
// (a) Displacement formulation (Bonet & Wood 2008, 8.3; Holzapfel 2000 §8.4):
//   F = I + sum_a u_a (x) dR_a/dX,  f_a = int P dR_a/dX dV with P = F S,
//   K_ab = int B_a^T C B_b dV + (int dR_a/dX . S dR_b/dX dV) I.
// (b) Mixed u–p–J three-field formulation (Simo, Taylor & Pister 1985; deal.II step-44) for laws
//   psi = psi_iso(C_bar, N, history) + U(J), with p~ and J~ in the element space of the element
//   pressure space (ElementView::pressure): Pi = int psi_iso + U(J~) + p~ (J - J~) dV. Stationarity
//   in p~ and J~, element by element:
//     J~ = Pi_e J        (M theta = int N J dV),
//     p~ = Pi_e U'(J~)   (M pi = int N U'(J~) dV),
//   so both are functions of u and Newton sees displacements only. The residual is that of (a)
//   with S = S_iso + p~ J C^-1, the tangent that of (a) with
//   C = C_iso + p~ J (C^-1 (x) C^-1 - 2 C^-1 (.) C^-1) plus the condensed volumetric term
//   K_vol = G^T M^-1 K_JJ M^-1 G,  G = int N (dJ/du) dV,  K_JJ = int N U''(J~) N^T dV,
//   which is symmetric (it is the second derivative of the reduced energy), so CHOLMOD applies.
//   With k = 0 this is the mean dilatation method: J~ = v_e / V_e, p~ = U'(J~),
//   K_vol = U''(J~)/V_e g g^T with g = int J F^-T dR/dX dV.
//   Newton iterations (step-44's static condensation): with theta, pi the coefficients of J~, p~
//   and the local residuals R_pi = int N J dV - M theta, R_theta = int N U'(J~) dV - M pi, Newton
//   on (u, theta, pi) condenses to
//     (K_uu + G^T A G) du = -(R_u + G^T (M^-1 R_theta + A R_pi)),  A = M^-1 K_JJ M^-1,
//     theta <- theta + M^-1 (R_pi + G du),  pi <- pi + M^-1 (R_theta + K_JJ dtheta).
//   Recomputing theta, pi as exact functions of u at every iterate instead (a penalty method)
//   feeds the second-order volume change of a large Newton step straight into the pressure,
//   kappa |grad du|^2, and with kappa/mu = 1e5 Newton then crawls (measured on Cook's membrane:
//   about 25 iterations per load step at kappa/mu = 1e3, no convergence at 1e5). So a kernel takes
//   either no base (exact projections, the first iterate of a step, outputs) or the base state of
//   the last tangent evaluation and updates theta, pi by the linearised local equations; both give
//   the same converged solution, where R_pi = R_theta = 0.
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "continuum/element_workspace.hpp"

namespace isomuscle::continuum {

// (a) Displacement formulation. Writes ws.fe (and ws.ke when tangent), ws.F, ws.S, ws.J.
KernelStatus displacement_kernel(const ElementView& el, const MaterialContext& mat, bool tangent,
                                 ElementWorkspace& ws);

// The element's state at the last tangent evaluation of the mixed formulation (views, m =
// pressure size, n = 3 n_en): displacements u_e (n), theta and pi (m), the local residuals R_pi and
// R_theta there (m), G (m x n, column-major) and K_JJ (m x m).
struct MixedBase {
  const double* ue = nullptr;
  const double* theta = nullptr;
  const double* pi = nullptr;
  const double* R_pi = nullptr;
  const double* R_theta = nullptr;
  const double* G = nullptr;
  const double* K_JJ = nullptr;
};

// (b) Mixed formulation; mat.law->has_volumetric_split() must be true; el.pressure holds the
// element functions N at the points, mass the Cholesky factor of M_e = int N N^T dV and
// mass_matrix M_e itself (m x m).
// base == nullptr: theta, pi are the exact projections at u_e; else the linearised update from
// base. Writes ws.fe (condensed residual), ws.ke (condensed tangent) when tangent, and ws.theta,
// ws.pi, ws.R_pi, ws.R_theta, ws.G, ws.K_JJ (the next base), ws.F, ws.S, ws.J, ws.J_bar, ws.p_bar.
KernelStatus mixed_kernel(const ElementView& el, const MaterialContext& mat,
                          const Eigen::LLT<Eigen::MatrixXd>& mass,
                          const Eigen::MatrixXd& mass_matrix, const MixedBase* base, bool tangent,
                          ElementWorkspace& ws);

}  // namespace isomuscle::continuum
