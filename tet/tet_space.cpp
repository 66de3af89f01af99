#include "tet/tet_space.hpp"

#include <Eigen/LU>
#include <sstream>
#include <stdexcept>
#include <string>

namespace isomuscle::tet {

// dN/dX = (dX/dxi)^-T dN/dxi, dV = w det(dX/dxi) at every element and point (header).
TetSpace::TetSpace(const TetMesh& mesh, int quadrature_degree)
    : mesh_(mesh), rule_(analysis_tet_rule(mesh.order, quadrature_degree)) {
  nen_ = tet_nodes(mesh.order);
  nqp_ = static_cast<int>(rule_.points.size());
  values_.resize(static_cast<std::size_t>(nqp_) * nen_);
  std::vector<Eigen::Vector3d> ref(static_cast<std::size_t>(nqp_) * nen_);
  for (int q = 0; q < nqp_; ++q) {
    tet_shape_values(mesh.order, rule_.points[q],
                     values_.data() + static_cast<std::size_t>(q) * nen_);
    tet_shape_gradients(mesh.order, rule_.points[q],
                        ref.data() + static_cast<std::size_t>(q) * nen_);
  }
  const int nel = mesh.num_elements();
  gradients_.resize(static_cast<std::size_t>(nel) * nqp_ * nen_);
  dv_.resize(static_cast<std::size_t>(nel) * nqp_);
  positions_.resize(static_cast<std::size_t>(nel) * nqp_);
  for (int e = 0; e < nel; ++e) {
    const auto el = mesh.element(e);
    for (int q = 0; q < nqp_; ++q) {
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      const std::size_t rq = static_cast<std::size_t>(q) * nen_;
      for (int a = 0; a < nen_; ++a) {
        J.noalias() += mesh.nodes[el[a]] * ref[rq + a].transpose();
        x += values_[rq + a] * mesh.nodes[el[a]];
      }
      const double det = J.determinant();
      if (!(det > 0.0)) {
        std::ostringstream msg;
        msg << "tetrahedron " << e << ", quadrature point " << q << ": det(dX/dxi) = " << det
            << " <= 0 (inverted or degenerate reference element)";
        throw std::invalid_argument(msg.str());
      }
      const Eigen::Matrix3d J_inv_t = J.inverse().transpose();
      const std::size_t i = static_cast<std::size_t>(e) * nqp_ + q;
      dv_[i] = rule_.weights[q] * det;
      positions_[i] = x;
      for (int a = 0; a < nen_; ++a) {
        gradients_[i * nen_ + a] = J_inv_t * ref[rq + a];
      }
    }
  }
}

}  // namespace isomuscle::tet
