#include "continuum/element_kernels.hpp"

#include <Eigen/LU>

#include "continuum/point_contributions.hpp"
#include "materials/kinematics.hpp"

namespace isomuscle::continuum {

namespace {

// N(X_q): the element pressure functions at point q (nqp x m, point-major).
const double* pressure_values(const ElementView& el, int q) {
  return el.pressure + static_cast<std::size_t>(q) * static_cast<std::size_t>(el.pressure_size);
}

// A failed kernel's status (no allocation).
KernelStatus failure(KernelStatus::Kind kind, int q, double value,
                     materials::PointStatus material = materials::PointStatus::ok) {
  KernelStatus s;
  s.kind = kind;
  s.point = q;
  s.value = value;
  s.material = material;
  return s;
}

// The law at point q with F (J = det F): the full response, or the isochoric part only (mixed
// formulation, S_iso and C_iso), with the point's committed and trial history.
KernelStatus evaluate_law(const MaterialContext& mat, int q, const Eigen::Matrix3d& F, double J,
                          bool isochoric, bool tangent, materials::PointInput& in,
                          materials::PointResult& out) {
  in.F = F;
  in.fibre = mat.fibres[q];
  bind_history(mat, q, mat.law->history_size(), in, out);
  const materials::PointStatus st = isochoric ? mat.law->evaluate_isochoric(in, out, tangent)
                                              : mat.law->evaluate(in, out, tangent);
  if (st != materials::PointStatus::ok) {
    return failure(KernelStatus::Kind::material, q, J, st);
  }
  return {};
}

}  // namespace

// (a) f_a = int F S dR_a/dX dV, K = int B^T C B + (dR/dX . S dR/dX) I dV (header).
KernelStatus displacement_kernel(const ElementView& el, const MaterialContext& mat, bool tangent,
                                 ElementWorkspace& ws) {
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
    const KernelStatus law_status = evaluate_law(mat, q, F, J, false, tangent, in, ws.result);
    if (!law_status.ok()) {
      return law_status;
    }
    if (!ws.result.S.allFinite() || (tangent && !ws.result.tangent.allFinite())) {
      return failure(KernelStatus::Kind::not_finite, q, J);
    }
    ws.S[q] = ws.result.S;
    add_point(F, ws.result.S, tangent ? &ws.result.tangent : nullptr, grad, el.dv[q], q, ws);
  }
  if (tangent) {
    add_point_stiffness(ws, el.nqp);
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
                          const Eigen::LLT<Eigen::MatrixXd>& mass,
                          const Eigen::MatrixXd& mass_matrix, const MixedBase* base, bool tangent,
                          ElementWorkspace& ws) {
  const Eigen::MatrixXd& M = mass_matrix;
  const int m = el.pressure_size;
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
    const Eigen::Map<const Eigen::VectorXd> N(pressure_values(el, q), m);
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
    const Eigen::Map<const Eigen::VectorXd> N(pressure_values(el, q), m);
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
    const Eigen::Map<const Eigen::VectorXd> N(pressure_values(el, q), m);
    const double p = N.dot(ws.pi);
    ws.p_bar[q] = p;
    const KernelStatus law_status = evaluate_law(mat, q, F, J, true, tangent, in, ws.result);
    if (!law_status.ok()) {
      return law_status;
    }
    const Eigen::Matrix3d F_inv = F.inverse();
    const Eigen::Matrix3d C_inv = F_inv * F_inv.transpose();
    const Eigen::Matrix3d S = ws.result.S + (p * J) * C_inv;
    if (!S.allFinite() || (tangent && !ws.result.tangent.allFinite())) {
      return failure(KernelStatus::Kind::not_finite, q, J);
    }
    ws.S[q] = S;
    if (tangent) {
      const materials::Vector6d ci = materials::voigt(C_inv);
      C = ws.result.tangent;
      C.noalias() += (p * J) * (ci * ci.transpose());
      C.noalias() -= (2.0 * p * J) * materials::symmetric_product_voigt(C_inv);
      add_point(F, S, &C, grad, el.dv[q], q, ws);
    } else {
      add_point(F, S, nullptr, grad, el.dv[q], q, ws);
    }
  }
  // A = M^-1 K_JJ M^-1; condensed residual correction G^T (M^-1 R_theta + A R_pi).
  ws.X = mass.solve(ws.K_JJ);
  ws.A = mass.solve(ws.X.transpose());
  ws.rhs = mass.solve(ws.R_theta);
  ws.rhs.noalias() += ws.A * ws.R_pi;
  ws.fe.noalias() += ws.G.transpose() * ws.rhs;
  if (tangent) {
    add_point_stiffness(ws, el.nqp);
    add_geometric(ws, el.nen);
    ws.AG.noalias() = ws.A * ws.G;
    ws.ke.triangularView<Eigen::Upper>() += ws.G.transpose() * ws.AG;
    finish_tangent(ws);
  }
  return {};
}

}  // namespace isomuscle::continuum
