#pragma once
// Element kernels of the total Lagrangian formulation on tetrahedra (DESIGN line 2: kernels
// separate from the loop that scatters them). Local DOF order 3 a + i (node a, component i). No
// heap allocation: everything lives in a TetWorkspace sized once per thread.
//
// (a) Displacement formulation (Bonet & Wood 2008, 8.3): F = I + sum_a u_a (x) dN_a/dX,
//   f_a = int F S dN_a/dX dV,  K = int B^T C B dV + (int dN_a/dX . S dN_b/dX dV) I.
// (b) Mixed u–p–J three-field formulation (Simo, Taylor & Pister 1985; deal.II step-44) for laws
//   psi = psi_iso + U(J), p~ and J~ discontinuous per element in span{phi_m}: m = 1 (constant,
//   phi = 1: mean dilatation) or m = 4 (linear, phi = 1, xi, eta, zeta). Condensed per element:
//   J~ = M^-1 int phi J dV, p~ = M^-1 int phi U'(J~) dV, S = S_iso + p~ J C^-1, and the tangent
//   gains the symmetric K_vol = G^T M^-1 K_JJ M^-1 G with G = int phi (dJ/du) dV,
//   K_JJ = int phi U''(J~) phi^T dV (the second derivative of the reduced energy).
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

#include "materials/material_law.hpp"

namespace isomuscle::tet {

// One element's tabulated reference data.
struct TetElementView {
  int nen = 0;
  int nqp = 0;
  const Eigen::Vector3d* gradients = nullptr;  // nqp x nen, dN/dX (1/m)
  const double* dv = nullptr;                  // nqp, w det(dX/dxi) (m^3)
  const double* pressure = nullptr;            // nqp x m, phi_m at the points
};

struct TetMaterialContext {
  const materials::MaterialLaw* law = nullptr;
  const Eigen::Vector3d* fibres = nullptr;    // nqp unit reference fibres
  double time = 0.0;                          // t + dt, s
  double dt = 0.0;                            // s
  const double* history_committed = nullptr;  // nqp x history_size
  double* history_trial = nullptr;            // nqp x history_size
};

struct TetKernelStatus {
  enum class Kind { ok, inverted, inverted_dilatation, material, not_finite };
  Kind kind = Kind::ok;
  int point = -1;
  double value = 0.0;
  materials::PointStatus material = materials::PointStatus::ok;
  bool ok() const { return kind == Kind::ok; }
};

class TetWorkspace {
 public:
  TetWorkspace() = default;
  TetWorkspace(int nen, int nqp, int pressure_size);

  Eigen::Matrix<double, 3, Eigen::Dynamic> ue;  // node displacements (m), column a
  Eigen::VectorXd fe;                           // internal force (N)
  Eigen::MatrixXd ke;                           // tangent (N/m)
  std::vector<Eigen::Matrix3d> F;
  std::vector<Eigen::Matrix3d> S;  // second Piola–Kirchhoff stress at every point, Pa
  std::vector<double> J;
  std::vector<double> J_bar;
  std::vector<double> p_bar;

  Eigen::Matrix<double, 6, Eigen::Dynamic> B, CB;
  Eigen::Matrix<double, 3, Eigen::Dynamic> SG, dJ;
  Eigen::MatrixXd H, G, K_JJ, X, A, AG;
  Eigen::VectorXd theta, pi, rhs;
  materials::PointResult result;
};

TetKernelStatus tet_displacement_kernel(const TetElementView& el, const TetMaterialContext& mat,
                                        bool tangent, TetWorkspace& ws);
// mass: Cholesky factor of M_e = int phi phi^T dV (m x m).
TetKernelStatus tet_mixed_kernel(const TetElementView& el, const TetMaterialContext& mat, int m,
                                 const Eigen::LLT<Eigen::MatrixXd>& mass, bool tangent,
                                 TetWorkspace& ws);

}  // namespace isomuscle::tet
