#include "continuum/point_contributions.hpp"

namespace isomuscle::continuum {

// The gradients are stored point-major: nqp blocks of nen vectors dN_a/dX.
ConstMap3X gradient_matrix(const ElementView& el, int q) {
  return ConstMap3X(el.gradients[static_cast<std::size_t>(q) * el.nen].data(), 3, el.nen);
}

// F = I + sum_a u_a (x) dN_a/dX (Bonet & Wood 2008, 8.3).
Eigen::Matrix3d deformation_gradient(const Matrix3X& ue, const ConstMap3X& grad) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F.noalias() += ue * grad.transpose();
  return F;
}

// B of dE = sym(F^T dF) in Voigt order 11, 22, 33, 2·12, 2·23, 2·13 (Bonet & Wood 2008, 8.3).
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

namespace {

// Upper triangles of K += B^T (C B dV) and H += dN/dX^T (S dN/dX dV) over the first `points`
// points kept in the workspace.
void add_kept_points(ElementWorkspace& ws, int points) {
  const Eigen::Index b_rows = 6 * static_cast<Eigen::Index>(points);
  const Eigen::Index g_rows = 3 * static_cast<Eigen::Index>(points);
  ws.ke.triangularView<Eigen::Upper>() +=
      ws.B_points.topRows(b_rows).transpose() * ws.CB_points.topRows(b_rows);
  ws.H.triangularView<Eigen::Upper>() +=
      ws.grad_points.topRows(g_rows).transpose() * ws.SG_points.topRows(g_rows);
}

}  // namespace

// f_a += P dN_a/dX dV with P = F S; with C, point q's factors of K += B^T C B dV and
// H += G^T S G dV (Bonet & Wood 2008, 8.3), added for every kPointsPerProduct points at once.
void add_point(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S, const materials::Matrix6d* C,
               const ConstMap3X& grad, double dv, int q, ElementWorkspace& ws) {
  const int nen = static_cast<int>(grad.cols());
  Eigen::Map<Matrix3X> f3(ws.fe.data(), 3, nen);
  const Eigen::Matrix3d P = dv * (F * S);
  f3.noalias() += P * grad;
  if (C != nullptr) {
    const int slot = q % kPointsPerProduct;
    fill_b(F, grad, ws.B);
    ws.B_points.middleRows<6>(6 * slot) = ws.B;
    ws.CB_points.middleRows<6>(6 * slot).noalias() = (dv * *C) * ws.B;
    ws.grad_points.middleRows<3>(3 * slot) = grad;
    ws.SG_points.middleRows<3>(3 * slot).noalias() = (dv * S) * grad;
    if (slot == kPointsPerProduct - 1)
      add_kept_points(ws, kPointsPerProduct);
  }
}

// The points after the last full group of kPointsPerProduct.
void add_point_stiffness(ElementWorkspace& ws, int nqp) {
  const int rest = nqp % kPointsPerProduct;
  if (rest > 0)
    add_kept_points(ws, rest);
}

// K(3a + i, 3b + i) += H(a, b), a <= b (Bonet & Wood 2008, 8.3: initial stress stiffness).
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

// K_e = K_e^T: copies the upper triangle into the lower one.
void finish_tangent(ElementWorkspace& ws) {
  ws.ke.triangularView<Eigen::StrictlyLower>() = ws.ke.transpose();
}

// History of point q: the q-th block of hs doubles of the element's arrays.
void bind_history(const MaterialContext& mat, int q, int hs, materials::PointInput& in,
                  materials::PointResult& out) {
  if (hs > 0) {
    const std::size_t off = static_cast<std::size_t>(q) * static_cast<std::size_t>(hs);
    in.history = std::span<const double>(mat.history_committed + off, hs);
    out.history = std::span<double>(mat.history_trial + off, hs);
  }
  in.trial_is_current = mat.trial_is_current;
}

}  // namespace isomuscle::continuum
