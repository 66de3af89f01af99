#include "iga/pressure_space.hpp"

#include <stdexcept>
#include <string>

namespace isomuscle::iga {

namespace {

// Legendre polynomials P_0..P_k at x by (n+1) P_{n+1} = (2n+1) x P_n - n P_{n-1}.
void legendre(int k, double x, double* p) {
  p[0] = 1.0;
  if (k >= 1) {
    p[1] = x;
  }
  for (int n = 1; n < k; ++n) {
    p[n + 1] = ((2.0 * n + 1.0) * x * p[n] - n * p[n - 1]) / (n + 1.0);
  }
}

}  // namespace

Eigen::Vector3d element_reference_coordinates(const Element& element, const Eigen::Vector3d& xi) {
  Eigen::Vector3d t;
  for (int d = 0; d < 3; ++d) {
    const double a = element.box[d][0];
    const double b = element.box[d][1];
    t[d] = (2.0 * xi[d] - a - b) / (b - a);
  }
  return t;
}

void PressureSpace::evaluate(const Eigen::Vector3d& t, double* out) const {
  double pu[5];
  double pv[5];
  double pw[5];
  legendre(degree_, t[0], pu);
  legendre(degree_, t[1], pv);
  legendre(degree_, t[2], pw);
  const int n = degree_ + 1;
  for (int l = 0; l < n; ++l) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        out[i + n * (j + n * l)] = pu[i] * pv[j] * pw[l];
      }
    }
  }
}

// Tabulates N at the quadrature points (from element 0: every element uses the same affine map of
// the tensor Gauss rule) and factorises M_e = sum_q N(t_q) N(t_q)^T dV_q per element.
PressureSpace::PressureSpace(const Space& space, int degree) : degree_(degree) {
  if (degree < 0 || degree > 4) {
    throw std::invalid_argument("mixed formulation: pressure degree " + std::to_string(degree) +
                                " outside the valid range 0..4 (0 = mean dilatation)");
  }
  m_ = (degree + 1) * (degree + 1) * (degree + 1);
  const int nqp = space.points_per_element();
  table_.resize(static_cast<std::size_t>(nqp) * m_);
  for (int q = 0; q < nqp; ++q) {
    const Eigen::Vector3d t =
        element_reference_coordinates(space.element(0), space.parametric(0, q));
    evaluate(t, table_.data() + static_cast<std::size_t>(q) * m_);
  }
  mass_.resize(space.num_elements());
  mass_matrix_.resize(space.num_elements());
  Eigen::MatrixXd M(m_, m_);
  for (int e = 0; e < space.num_elements(); ++e) {
    M.setZero();
    for (int q = 0; q < nqp; ++q) {
      const Eigen::Map<const Eigen::VectorXd> N(values(q), m_);
      M.noalias() += space.dv(e, q) * N * N.transpose();
    }
    mass_matrix_[e] = M;
    mass_[e].compute(M);
    if (mass_[e].info() != Eigen::Success) {
      throw std::invalid_argument("mixed formulation: the pressure mass matrix of element " +
                                  std::to_string(e) + " is not positive definite (degree " +
                                  std::to_string(degree) + " needs at least " +
                                  std::to_string(degree + 1) + " quadrature points per direction)");
    }
  }
}

}  // namespace isomuscle::iga
