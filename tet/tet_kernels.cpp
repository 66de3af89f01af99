#include "tet/tet_kernels.hpp"

#include <Eigen/LU>
#include <span>

#include "materials/kinematics.hpp"

namespace isomuscle::tet {

namespace {

using Matrix3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;
using ConstMap3X = Eigen::Map<const Matrix3X>;

ConstMap3X gradient_matrix(const TetElementView& el, int q) {
  return ConstMap3X(el.gradients[static_cast<std::size_t>(q) * el.nen].data(), 3, el.nen);
}

// F = I + sum_a u_a (x) dN_a/dX.
Eigen::Matrix3d deformation_gradient(const Matrix3X& ue, const ConstMap3X& grad) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F.noalias() += ue * grad.transpose();
  return F;
}

// Voigt B of dE = sym(F^T dF), order 11, 22, 33, 2·12, 2·23, 2·13 (Bonet & Wood 2008, 8.3).
void fill_b(const Eigen::Matrix3d& F, const ConstMap3X& grad,
            Eigen::Matrix<double, 6, Eigen::Dynamic>& B) {
  for (int a = 0; a < grad.cols(); ++a) {
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

// f_a += F S dN_a/dX dV; K += B^T C B dV; H += dN/dX . S dN/dX dV.
void add_point(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S, const materials::Matrix6d* C,
               const ConstMap3X& grad, double dv, TetWorkspace& ws) {
  Eigen::Map<Matrix3X> f3(ws.fe.data(), 3, grad.cols());
  const Eigen::Matrix3d P = dv * (F * S);
  f3.noalias() += P * grad;
  if (C != nullptr) {
    fill_b(F, grad, ws.B);
    ws.CB.noalias() = (dv * *C) * ws.B;
    ws.ke.noalias() += ws.B.transpose() * ws.CB;
    ws.SG.noalias() = (dv * S) * grad;
    ws.H.noalias() += grad.transpose() * ws.SG;
  }
}

// K(3a + i, 3b + i) += H(a, b): the geometric stiffness.
void add_geometric(TetWorkspace& ws, int nen) {
  for (int b = 0; b < nen; ++b) {
    for (int a = 0; a < nen; ++a) {
      for (int i = 0; i < 3; ++i) {
        ws.ke(3 * a + i, 3 * b + i) += ws.H(a, b);
      }
    }
  }
}

TetKernelStatus failure(TetKernelStatus::Kind kind, int q, double value,
                        materials::PointStatus material = materials::PointStatus::ok) {
  TetKernelStatus s;
  s.kind = kind;
  s.point = q;
  s.value = value;
  s.material = material;
  return s;
}

void bind_history(const TetMaterialContext& mat, int q, int hs, materials::PointInput& in,
                  materials::PointResult& out) {
  if (hs > 0) {
    const std::size_t off = static_cast<std::size_t>(q) * hs;
    in.history = std::span<const double>(mat.history_committed + off, hs);
    out.history = std::span<double>(mat.history_trial + off, hs);
  }
}

}  // namespace

TetWorkspace::TetWorkspace(int nen, int nqp, int pressure_size) {
  const int n = 3 * nen;
  const int m = pressure_size;
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
  G.setZero(m, n);
  K_JJ.setZero(m, m);
  X.setZero(m, m);
  A.setZero(m, m);
  AG.setZero(m, n);
  theta.setZero(m);
  pi.setZero(m);
  rhs.setZero(m);
}

// (a) Displacement formulation (header).
TetKernelStatus tet_displacement_kernel(const TetElementView& el, const TetMaterialContext& mat,
                                        bool tangent, TetWorkspace& ws) {
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
    ws.F[q] = deformation_gradient(ws.ue, grad);
    const double J = ws.F[q].determinant();
    ws.J[q] = J;
    if (!(J > 0.0)) {
      return failure(TetKernelStatus::Kind::inverted, q, J);
    }
    in.F = ws.F[q];
    in.fibre = mat.fibres[q];
    bind_history(mat, q, hs, in, ws.result);
    const materials::PointStatus st = mat.law->evaluate(in, ws.result, tangent);
    if (st != materials::PointStatus::ok) {
      return failure(TetKernelStatus::Kind::material, q, J, st);
    }
    if (!ws.result.S.allFinite() || (tangent && !ws.result.tangent.allFinite())) {
      return failure(TetKernelStatus::Kind::not_finite, q, J);
    }
    ws.S[q] = ws.result.S;
    add_point(ws.F[q], ws.result.S, tangent ? &ws.result.tangent : nullptr, grad, el.dv[q], ws);
  }
  if (tangent) {
    add_geometric(ws, el.nen);
  }
  return {};
}

// (b) Mixed formulation, condensed (header).
TetKernelStatus tet_mixed_kernel(const TetElementView& el, const TetMaterialContext& mat, int m,
                                 const Eigen::LLT<Eigen::MatrixXd>& mass, bool tangent,
                                 TetWorkspace& ws) {
  const int hs = mat.law->history_size();
  ws.fe.setZero();
  if (tangent) {
    ws.ke.setZero();
    ws.H.setZero();
    ws.G.setZero();
    ws.K_JJ.setZero();
  }
  ws.rhs.setZero();
  for (int q = 0; q < el.nqp; ++q) {
    ws.F[q] = deformation_gradient(ws.ue, gradient_matrix(el, q));
    const double J = ws.F[q].determinant();
    ws.J[q] = J;
    if (!(J > 0.0)) {
      return failure(TetKernelStatus::Kind::inverted, q, J);
    }
    const Eigen::Map<const Eigen::VectorXd> phi(el.pressure + static_cast<std::size_t>(q) * m, m);
    ws.rhs.noalias() += (J * el.dv[q]) * phi;
  }
  ws.theta = mass.solve(ws.rhs);
  ws.rhs.setZero();
  for (int q = 0; q < el.nqp; ++q) {
    const Eigen::Map<const Eigen::VectorXd> phi(el.pressure + static_cast<std::size_t>(q) * m, m);
    const double Jb = phi.dot(ws.theta);
    ws.J_bar[q] = Jb;
    if (!(Jb > 0.0)) {
      return failure(TetKernelStatus::Kind::inverted_dilatation, q, Jb);
    }
    const Eigen::Vector3d U = mat.law->volumetric(Jb);
    if (!U.allFinite()) {
      return failure(TetKernelStatus::Kind::not_finite, q, Jb);
    }
    ws.rhs.noalias() += (U[1] * el.dv[q]) * phi;
    if (tangent) {
      ws.K_JJ.noalias() += (U[2] * el.dv[q]) * phi * phi.transpose();
    }
  }
  ws.pi = mass.solve(ws.rhs);
  materials::PointInput in;
  in.time = mat.time;
  in.dt = mat.dt;
  materials::Matrix6d C;
  for (int q = 0; q < el.nqp; ++q) {
    const ConstMap3X grad = gradient_matrix(el, q);
    const Eigen::Matrix3d& F = ws.F[q];
    const double J = ws.J[q];
    const Eigen::Map<const Eigen::VectorXd> phi(el.pressure + static_cast<std::size_t>(q) * m, m);
    const double p = phi.dot(ws.pi);
    ws.p_bar[q] = p;
    in.F = F;
    in.fibre = mat.fibres[q];
    bind_history(mat, q, hs, in, ws.result);
    const materials::PointStatus st = mat.law->evaluate_isochoric(in, ws.result, tangent);
    if (st != materials::PointStatus::ok) {
      return failure(TetKernelStatus::Kind::material, q, J, st);
    }
    const Eigen::Matrix3d F_inv = F.inverse();
    const Eigen::Matrix3d C_inv = F_inv * F_inv.transpose();
    const Eigen::Matrix3d S = ws.result.S + (p * J) * C_inv;
    if (!S.allFinite() || (tangent && !ws.result.tangent.allFinite())) {
      return failure(TetKernelStatus::Kind::not_finite, q, J);
    }
    ws.S[q] = S;
    if (tangent) {
      const materials::Vector6d ci = materials::voigt(C_inv);
      C = ws.result.tangent;
      C.noalias() += (p * J) * (ci * ci.transpose());
      C.noalias() -= (2.0 * p * J) * materials::symmetric_product_voigt(C_inv);
      ws.dJ.noalias() = (J * F_inv.transpose()) * grad;
      const Eigen::Map<const Eigen::RowVectorXd> dj(ws.dJ.data(), 3 * el.nen);
      ws.G.noalias() += (el.dv[q] * phi) * dj;
      add_point(F, S, &C, grad, el.dv[q], ws);
    } else {
      add_point(F, S, nullptr, grad, el.dv[q], ws);
    }
  }
  if (tangent) {
    add_geometric(ws, el.nen);
    ws.X = mass.solve(ws.K_JJ);
    ws.A = mass.solve(ws.X.transpose());
    ws.AG.noalias() = ws.A * ws.G;
    ws.ke.noalias() += ws.G.transpose() * ws.AG;
  }
  return {};
}

}  // namespace isomuscle::tet
