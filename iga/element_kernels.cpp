#include "iga/element_kernels.hpp"

#include <Eigen/LU>
#include <cmath>

#include "materials/kinematics.hpp"

namespace isomuscle::iga {

namespace {

using Matrix3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;
using ConstMap3X = Eigen::Map<const Matrix3X>;

ConstMap3X gradient_matrix(const ElementView& el, int q) {
  return ConstMap3X(el.gradients[static_cast<std::size_t>(q) * el.nen].data(), 3, el.nen);
}

// F = I + sum_a u_a (x) dR_a/dX (the deformation gradient of the total Lagrangian map).
Eigen::Matrix3d deformation_gradient(const Matrix3X& ue, const ConstMap3X& grad) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F.noalias() += ue * grad.transpose();
  return F;
}

// Voigt strain-displacement matrix of dE = sym(F^T dF), order 11, 22, 33, 2·12, 2·23, 2·13
// (Bonet & Wood 2008, 8.3): columns 3a + k.
void fill_b(const Eigen::Matrix3d& F, const ConstMap3X& grad,
            Eigen::Matrix<double, 6, Eigen::Dynamic>& B) {
  const int nen = static_cast<int>(grad.cols());
  for (int a = 0; a < nen; ++a) {
    const double g0 = grad(0, a);
    const double g1 = grad(1, a);
    const double g2 = grad(2, a);
    for (int k = 0; k < 3; ++k) {
      const int c = 3 * a + k;
      B(0, c) = F(k, 0) * g0;
      B(1, c) = F(k, 1) * g1;
      B(2, c) = F(k, 2) * g2;
      B(3, c) = F(k, 0) * g1 + F(k, 1) * g0;
      B(4, c) = F(k, 1) * g2 + F(k, 2) * g1;
      B(5, c) = F(k, 0) * g2 + F(k, 2) * g0;
    }
  }
}

// Adds one quadrature point: f_a += P dR_a/dX dV; K += B^T C B dV; H += G^T S G dV (geometric).
void add_point(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S, const materials::Matrix6d* C,
               const ConstMap3X& grad, double dv, ElementWorkspace& ws) {
  const int nen = static_cast<int>(grad.cols());
  Eigen::Map<Matrix3X> f3(ws.fe.data(), 3, nen);
  const Eigen::Matrix3d P = dv * (F * S);
  f3.noalias() += P * grad;
  if (C != nullptr) {
    fill_b(F, grad, ws.B);
    // Only the upper triangles: K_e and H are symmetric (C and S are), finish_tangent mirrors.
    ws.CB.noalias() = (dv * *C) * ws.B;
    ws.ke.triangularView<Eigen::Upper>() += ws.B.transpose() * ws.CB;
    ws.SG.noalias() = (dv * S) * grad;
    ws.H.triangularView<Eigen::Upper>() += grad.transpose() * ws.SG;
  }
}

// K(3a + i, 3b + i) += H(a, b) for a <= b: the geometric (initial stress) stiffness, upper part.
void add_geometric(ElementWorkspace& ws, int nen) {
  for (int b = 0; b < nen; ++b) {
    for (int a = 0; a <= b; ++a) {
      const double h = ws.H(a, b);
      for (int i = 0; i < 3; ++i) {
        ws.ke(3 * a + i, 3 * b + i) += h;
      }
    }
  }
}

// The lower triangle of K_e from the upper one (K_e is symmetric).
void finish_tangent(ElementWorkspace& ws) {
  ws.ke.triangularView<Eigen::StrictlyLower>() = ws.ke.transpose();
}

bool finite(const Eigen::Matrix3d& S) {
  return S.allFinite();
}

KernelStatus failure(KernelStatus::Kind kind, int q, double value,
                     materials::PointStatus material = materials::PointStatus::ok) {
  KernelStatus s;
  s.kind = kind;
  s.point = q;
  s.value = value;
  s.material = material;
  return s;
}

}  // namespace

ElementView element_view(const Space& space, int e) {
  ElementView v;
  v.nen = space.functions_per_element();
  v.nqp = space.points_per_element();
  v.values = space.values(e, 0).data();
  v.gradients = space.gradients(e, 0).data();
  v.dv = space.element_dv(e).data();
  return v;
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
  CB.setZero(6, n);
  SG.setZero(3, nen);
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

// (a) f_a = int F S dR_a/dX dV, K = int B^T C B + (dR/dX . S dR/dX) I dV (header).
KernelStatus displacement_kernel(const ElementView& el, const MaterialContext& mat, bool tangent,
                                 ElementWorkspace& ws) {
  const int hs = mat.law->history_size();
  ws.fe.setZero();
  if (tangent) {
    ws.ke.setZero();
    ws.H.setZero();
  }
  materials::PointInput in;
  in.time = mat.time;
  in.dt = mat.dt;
  for (int q = 0; q < el.nqp; ++q) {
    const ConstMap3X grad = gradient_matrix(el, q);
    const Eigen::Matrix3d F = deformation_gradient(ws.ue, grad);
    const double J = F.determinant();
    ws.F[q] = F;
    ws.J[q] = J;
    if (!(J > 0.0)) {
      return failure(KernelStatus::Kind::inverted, q, J);
    }
    in.F = F;
    in.fibre = mat.fibres[q];
    if (hs > 0) {
      in.history =
          std::span<const double>(mat.history_committed + static_cast<std::size_t>(q) * hs, hs);
      ws.result.history =
          std::span<double>(mat.history_trial + static_cast<std::size_t>(q) * hs, hs);
    }
    const materials::PointStatus st = mat.law->evaluate(in, ws.result, tangent);
    if (st != materials::PointStatus::ok) {
      return failure(KernelStatus::Kind::material, q, J, st);
    }
    if (!finite(ws.result.S) || (tangent && !ws.result.tangent.allFinite())) {
      return failure(KernelStatus::Kind::not_finite, q, J);
    }
    ws.S[q] = ws.result.S;
    add_point(F, ws.result.S, tangent ? &ws.result.tangent : nullptr, grad, el.dv[q], ws);
  }
  if (tangent) {
    add_geometric(ws, el.nen);
    finish_tangent(ws);
  }
  return {};
}

// (b) The element's local unknowns theta (J~ coefficients) and pi (p~ coefficients) come either
// from the exact projections (base == nullptr: theta = M^-1 int N J, pi = M^-1 int N U'(J~)) or
// from the Newton update of the local equations linearised at the base state (header); then the
// local residuals R_pi = int N J - M theta, R_theta = int N U'(J~) - M pi, the displacement
// residual with p~ = N . pi, and the condensed residual and tangent
//   r = R_u + G^T (M^-1 R_theta + A R_pi),  K = K_uu + G^T A G,  A = M^-1 K_JJ M^-1.
KernelStatus mixed_kernel(const ElementView& el, const MaterialContext& mat,
                          const PressureSpace& pressure, int element, const MixedBase* base,
                          bool tangent, ElementWorkspace& ws) {
  const Eigen::LLT<Eigen::MatrixXd>& mass = pressure.mass(element);
  const Eigen::MatrixXd& M = pressure.mass_matrix(element);
  const int hs = mat.law->history_size();
  const int m = pressure.size();
  const int n = 3 * el.nen;
  ws.fe.setZero();
  ws.G.setZero();
  ws.K_JJ.setZero();
  if (tangent) {
    ws.ke.setZero();
    ws.H.setZero();
  }
  // Pass 1: F, J, int N J dV and G = int N (dJ/du)^T dV with dJ/du_a = J F^-T dR_a/dX.
  ws.R_pi.setZero();
  for (int q = 0; q < el.nqp; ++q) {
    const ConstMap3X grad = gradient_matrix(el, q);
    ws.F[q] = deformation_gradient(ws.ue, grad);
    const double J = ws.F[q].determinant();
    ws.J[q] = J;
    if (!(J > 0.0)) {
      return failure(KernelStatus::Kind::inverted, q, J);
    }
    const Eigen::Map<const Eigen::VectorXd> N(pressure.values(q), m);
    ws.R_pi.noalias() += (J * el.dv[q]) * N;
    ws.dJ.noalias() = (J * ws.F[q].inverse().transpose()) * grad;
    const Eigen::Map<const Eigen::RowVectorXd> dj(ws.dJ.data(), n);
    ws.G.noalias() += (el.dv[q] * N) * dj;
  }
  if (base == nullptr) {
    ws.theta = mass.solve(ws.R_pi);  // exact projection of J
  } else {
    // theta = theta_b + M^-1 (R_pi,b + G_b (u_e - u_e,b)).
    const Eigen::Map<const Eigen::VectorXd> ue_b(base->ue, n);
    const Eigen::Map<const Eigen::VectorXd> ue(ws.ue.data(), n);
    const Eigen::Map<const Eigen::MatrixXd> G_b(base->G, m, n);
    ws.rhs = Eigen::Map<const Eigen::VectorXd>(base->R_pi, m);
    ws.rhs.noalias() += G_b * (ue - ue_b);
    ws.theta = mass.solve(ws.rhs);
    ws.theta += Eigen::Map<const Eigen::VectorXd>(base->theta, m);
  }
  ws.R_pi.noalias() -= M * ws.theta;
  // U'(J~) at the points: int N U'(J~) dV and K_JJ = int N U''(J~) N^T dV.
  ws.R_theta.setZero();
  for (int q = 0; q < el.nqp; ++q) {
    const Eigen::Map<const Eigen::VectorXd> N(pressure.values(q), m);
    const double Jb = N.dot(ws.theta);
    ws.J_bar[q] = Jb;
    if (!(Jb > 0.0)) {
      return failure(KernelStatus::Kind::inverted_dilatation, q, Jb);
    }
    const Eigen::Vector3d U = mat.law->volumetric(Jb);
    if (!U.allFinite()) {
      return failure(KernelStatus::Kind::not_finite, q, Jb);
    }
    ws.R_theta.noalias() += (U[1] * el.dv[q]) * N;
    ws.K_JJ.noalias() += (U[2] * el.dv[q]) * N * N.transpose();
  }
  if (base == nullptr) {
    ws.pi = mass.solve(ws.R_theta);  // exact projection of U'(J~)
  } else {
    // pi = pi_b + M^-1 (R_theta,b + K_JJ,b (theta - theta_b)).
    const Eigen::Map<const Eigen::MatrixXd> K_b(base->K_JJ, m, m);
    ws.rhs = Eigen::Map<const Eigen::VectorXd>(base->R_theta, m);
    ws.rhs.noalias() += K_b * (ws.theta - Eigen::Map<const Eigen::VectorXd>(base->theta, m));
    ws.pi = mass.solve(ws.rhs);
    ws.pi += Eigen::Map<const Eigen::VectorXd>(base->pi, m);
  }
  ws.R_theta.noalias() -= M * ws.pi;
  // Pass 2: isochoric response + p~ J C^-1.
  materials::PointInput in;
  in.time = mat.time;
  in.dt = mat.dt;
  materials::Matrix6d C;
  for (int q = 0; q < el.nqp; ++q) {
    const ConstMap3X grad = gradient_matrix(el, q);
    const Eigen::Matrix3d& F = ws.F[q];
    const double J = ws.J[q];
    const Eigen::Map<const Eigen::VectorXd> N(pressure.values(q), m);
    const double p = N.dot(ws.pi);
    ws.p_bar[q] = p;
    in.F = F;
    in.fibre = mat.fibres[q];
    if (hs > 0) {
      in.history =
          std::span<const double>(mat.history_committed + static_cast<std::size_t>(q) * hs, hs);
      ws.result.history =
          std::span<double>(mat.history_trial + static_cast<std::size_t>(q) * hs, hs);
    }
    const materials::PointStatus st = mat.law->evaluate_isochoric(in, ws.result, tangent);
    if (st != materials::PointStatus::ok) {
      return failure(KernelStatus::Kind::material, q, J, st);
    }
    const Eigen::Matrix3d F_inv = F.inverse();
    const Eigen::Matrix3d C_inv = F_inv * F_inv.transpose();
    const Eigen::Matrix3d S = ws.result.S + (p * J) * C_inv;
    if (!finite(S) || (tangent && !ws.result.tangent.allFinite())) {
      return failure(KernelStatus::Kind::not_finite, q, J);
    }
    ws.S[q] = S;
    if (tangent) {
      const materials::Vector6d ci = materials::voigt(C_inv);
      C = ws.result.tangent;
      C.noalias() += (p * J) * (ci * ci.transpose());
      C.noalias() -= (2.0 * p * J) * materials::symmetric_product_voigt(C_inv);
      add_point(F, S, &C, grad, el.dv[q], ws);
    } else {
      add_point(F, S, nullptr, grad, el.dv[q], ws);
    }
  }
  // A = M^-1 K_JJ M^-1; condensed residual correction G^T (M^-1 R_theta + A R_pi).
  ws.X = mass.solve(ws.K_JJ);
  ws.A = mass.solve(ws.X.transpose());
  ws.rhs = mass.solve(ws.R_theta);
  ws.rhs.noalias() += ws.A * ws.R_pi;
  ws.fe.noalias() += ws.G.transpose() * ws.rhs;
  if (tangent) {
    add_geometric(ws, el.nen);
    ws.AG.noalias() = ws.A * ws.G;
    ws.ke.triangularView<Eigen::Upper>() += ws.G.transpose() * ws.AG;
    finish_tangent(ws);
  }
  return {};
}

}  // namespace isomuscle::iga
