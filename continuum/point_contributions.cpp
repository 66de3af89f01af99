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

// f_a += P dN_a/dX dV with P = F S; K += B^T C B dV; H += G^T S G dV (Bonet & Wood 2008, 8.3).
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
}

}  // namespace isomuscle::continuum
