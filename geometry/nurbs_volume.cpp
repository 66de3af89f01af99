// Trivariate NURBS solids (thesis 5.13) and their rational basis (thesis 5.6 and 5.11 extended to
// three directions). evaluate_basis_in_span is the hot path of IGA assembly: no heap allocation
// once `out` has the right size.
#include "geometry/nurbs_volume.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "geometry/bspline_basis.hpp"

namespace isomuscle::geometry {

namespace {

constexpr int kScratch = 2 * (kMaxDegree + 1);

std::string triple(int i, int j, int k) {
  return "(" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) + ")";
}

}  // namespace

// Checks counts (n_u n_v n_w, index i + n_u (j + n_v k)) and finiteness/positivity.
NurbsVolume::NurbsVolume(std::array<KnotVector, 3> knots, std::vector<Eigen::Vector3d> points,
                         std::vector<double> weights)
    : knots_(std::move(knots)), points_(std::move(points)), weights_(std::move(weights)) {
  for (int d = 0; d < 3; ++d) {
    if (knots_[d].size() == 0) {
      throw std::invalid_argument("NurbsVolume: empty knot vector in direction " +
                                  std::to_string(d));
    }
  }
  const std::size_t n = static_cast<std::size_t>(count(0)) * static_cast<std::size_t>(count(1)) *
                        static_cast<std::size_t>(count(2));
  if (points_.size() != n || weights_.size() != n) {
    throw std::invalid_argument(
        "NurbsVolume: the knot vectors need " + std::to_string(count(0)) + " x " +
        std::to_string(count(1)) + " x " + std::to_string(count(2)) + " = " + std::to_string(n) +
        " control points and weights, got " + std::to_string(points_.size()) + " points and " +
        std::to_string(weights_.size()) + " weights");
  }
  for (std::size_t a = 0; a < n; ++a) {
    const int i = static_cast<int>(a) % count(0);
    const int j = (static_cast<int>(a) / count(0)) % count(1);
    const int k = static_cast<int>(a) / (count(0) * count(1));
    if (!points_[a].allFinite()) {
      throw std::invalid_argument("NurbsVolume: control point " + triple(i, j, k) +
                                  " is not finite");
    }
    if (!(std::isfinite(weights_[a]) && weights_[a] > 0.0)) {
      throw std::invalid_argument("NurbsVolume: weight " + triple(i, j, k) + " = " +
                                  std::to_string(weights_[a]) + " must be finite and positive");
    }
  }
}

// H(xi) = sum_ijk N_i N_j N_k w_ijk P_ijk / sum_ijk N_i N_j N_k w_ijk (thesis 5.13).
Eigen::Vector3d NurbsVolume::evaluate(const Eigen::Vector3d& xi) const {
  const int p = degree(0);
  const int q = degree(1);
  const int r = degree(2);
  const int s0 = knots_[0].find_span(xi[0]);
  const int s1 = knots_[1].find_span(xi[1]);
  const int s2 = knots_[2].find_span(xi[2]);
  double N0[kMaxDegree + 1];
  double N1[kMaxDegree + 1];
  double N2[kMaxDegree + 1];
  basis_functions(knots_[0], s0, xi[0], N0);
  basis_functions(knots_[1], s1, xi[1], N1);
  basis_functions(knots_[2], s2, xi[2], N2);
  Eigen::Vector3d A = Eigen::Vector3d::Zero();
  double W = 0.0;
  for (int c = 0; c <= r; ++c) {
    for (int b = 0; b <= q; ++b) {
      const double nbc = N1[b] * N2[c];
      const int row = count(0) * ((s1 - q + b) + count(1) * (s2 - r + c));
      for (int a = 0; a <= p; ++a) {
        const int idx = row + s0 - p + a;
        const double n = N0[a] * nbc * weights_[idx];
        A.noalias() += n * points_[idx];
        W += n;
      }
    }
  }
  return A / W;
}

Eigen::Matrix3d NurbsVolume::jacobian(const Eigen::Vector3d& xi) const {
  Eigen::Vector3d point;
  Eigen::Matrix3d jac;
  evaluate_with_jacobian(xi, point, jac);
  return jac;
}

// Point and Jacobian dH/dxi by the quotient rule on the homogeneous sums A = sum N w P and
// W = sum N w: H = A / W, dH/dxi_d = (dA/dxi_d - H dW/dxi_d) / W (NURBS Book eq. 4.20 in 3D).
// Units: point units, point units per parameter unit.
void NurbsVolume::evaluate_with_jacobian(const Eigen::Vector3d& xi, Eigen::Vector3d& point,
                                         Eigen::Matrix3d& jacobian) const {
  const int p = degree(0);
  const int q = degree(1);
  const int r = degree(2);
  const int s0 = knots_[0].find_span(xi[0]);
  const int s1 = knots_[1].find_span(xi[1]);
  const int s2 = knots_[2].find_span(xi[2]);
  double N0[kScratch];
  double N1[kScratch];
  double N2[kScratch];
  basis_first_derivatives(knots_[0], s0, xi[0], N0);
  basis_first_derivatives(knots_[1], s1, xi[1], N1);
  basis_first_derivatives(knots_[2], s2, xi[2], N2);
  Eigen::Vector3d A = Eigen::Vector3d::Zero();
  Eigen::Matrix3d dA = Eigen::Matrix3d::Zero();
  double W = 0.0;
  Eigen::Vector3d dW = Eigen::Vector3d::Zero();
  for (int c = 0; c <= r; ++c) {
    for (int b = 0; b <= q; ++b) {
      const double v00 = N1[b] * N2[c];
      const double v10 = N1[q + 1 + b] * N2[c];
      const double v01 = N1[b] * N2[r + 1 + c];
      const int row = count(0) * ((s1 - q + b) + count(1) * (s2 - r + c));
      for (int a = 0; a <= p; ++a) {
        const int idx = row + s0 - p + a;
        const double w = weights_[idx];
        const double n = N0[a] * v00 * w;
        const Eigen::Vector3d g(N0[p + 1 + a] * v00 * w, N0[a] * v10 * w, N0[a] * v01 * w);
        A.noalias() += n * points_[idx];
        dA.noalias() += points_[idx] * g.transpose();
        W += n;
        dW += g;
      }
    }
  }
  point = A / W;
  jacobian = (dA - point * dW.transpose()) / W;
}

void NurbsVolume::evaluate_basis(const Eigen::Vector3d& xi, VolumeBasis& out) const {
  const std::array<int, 3> span = {knots_[0].find_span(xi[0]), knots_[1].find_span(xi[1]),
                                   knots_[2].find_span(xi[2])};
  evaluate_basis_in_span(span, xi, out);
}

// R_a = N_a w_a / W, dR_a/dxi = (dN_a w_a - R_a dW/dxi) / W with W = sum_b N_b w_b (thesis 5.6,
// 5.11 in three directions). Local order: a = i + (p+1)(j + (q+1)k) over the span's functions.
void NurbsVolume::evaluate_basis_in_span(const std::array<int, 3>& span, const Eigen::Vector3d& xi,
                                         VolumeBasis& out) const {
  for (int d = 0; d < 3; ++d) {
    if (span[d] < degree(d) || span[d] >= count(d)) {
      throw std::out_of_range("NurbsVolume::evaluate_basis_in_span: span " +
                              std::to_string(span[d]) + " in direction " + std::to_string(d) +
                              " is outside " + std::to_string(degree(d)) + ".." +
                              std::to_string(count(d) - 1));
    }
  }
  const int p = degree(0);
  const int q = degree(1);
  const int r = degree(2);
  double N0[kScratch];
  double N1[kScratch];
  double N2[kScratch];
  basis_first_derivatives(knots_[0], span[0], xi[0], N0);
  basis_first_derivatives(knots_[1], span[1], xi[1], N1);
  basis_first_derivatives(knots_[2], span[2], xi[2], N2);
  const std::size_t nen = static_cast<std::size_t>((p + 1) * (q + 1) * (r + 1));
  if (out.index.size() != nen) {
    out.index.resize(nen);
  }
  if (out.value.size() != nen) {
    out.value.resize(nen);
  }
  if (out.derivative.size() != nen) {
    out.derivative.resize(nen);
  }
  // First pass: homogeneous products N_a w_a and their gradients, and their sums W, dW.
  double W = 0.0;
  Eigen::Vector3d dW = Eigen::Vector3d::Zero();
  std::size_t l = 0;
  for (int c = 0; c <= r; ++c) {
    for (int b = 0; b <= q; ++b) {
      const double v00 = N1[b] * N2[c];
      const double v10 = N1[q + 1 + b] * N2[c];
      const double v01 = N1[b] * N2[r + 1 + c];
      const int row = count(0) * ((span[1] - q + b) + count(1) * (span[2] - r + c));
      for (int a = 0; a <= p; ++a, ++l) {
        const int idx = row + span[0] - p + a;
        const double w = weights_[idx];
        out.index[l] = idx;
        out.value[l] = N0[a] * v00 * w;
        out.derivative[l] =
            Eigen::Vector3d(N0[p + 1 + a] * v00 * w, N0[a] * v10 * w, N0[a] * v01 * w);
        W += out.value[l];
        dW += out.derivative[l];
      }
    }
  }
  // Second pass: quotient rule.
  const double inv_w = 1.0 / W;
  for (std::size_t a = 0; a < nen; ++a) {
    out.value[a] *= inv_w;
    out.derivative[a] = (out.derivative[a] - out.value[a] * dW) * inv_w;
  }
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> NurbsVolume::bounding_box() const {
  Eigen::Vector3d lo = points_.front();
  Eigen::Vector3d hi = points_.front();
  for (const Eigen::Vector3d& x : points_) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return {lo, hi};
}

}  // namespace isomuscle::geometry
