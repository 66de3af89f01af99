#pragma once
// Reference data of a tetrahedral mesh tabulated once per element and quadrature point (total
// Lagrangian: nothing changes with the deformation): dN/dX = J^-T dN/dxi, dV = w det(dX/dxi), the
// reference position of each point. Isoparametric: curved 10-node elements are handled exactly.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "tet/tet_elements.hpp"
#include "tet/tet_mesh.hpp"

namespace isomuscle::tet {

class TetSpace {
 public:
  // mesh must outlive the space. the rule is analysis_tet_rule(order, quadrature_degree). Throws
  // std::invalid_argument naming the element and point where det(dX/dxi) <= 0.
  explicit TetSpace(const TetMesh& mesh, int quadrature_degree = 0);

  const TetMesh& mesh() const { return mesh_; }
  const TetRule& rule() const { return rule_; }
  int num_elements() const { return mesh_.num_elements(); }
  int nodes_per_element() const { return nen_; }
  int points_per_element() const { return nqp_; }
  int num_points() const { return nqp_ * mesh_.num_elements(); }

  // N_a at point q (same for every element).
  std::span<const double> values(int q) const {
    return {values_.data() + static_cast<std::size_t>(q) * nen_, static_cast<std::size_t>(nen_)};
  }
  // dN_a/dX at point q of element e (1/m), nen vectors; the element's block is contiguous.
  const Eigen::Vector3d* gradients(int e, int q) const {
    return gradients_.data() + (static_cast<std::size_t>(e) * nqp_ + q) * nen_;
  }
  const double* dv(int e) const { return dv_.data() + static_cast<std::size_t>(e) * nqp_; }
  const Eigen::Vector3d& position(int e, int q) const {
    return positions_[static_cast<std::size_t>(e) * nqp_ + q];
  }

 private:
  const TetMesh& mesh_;
  TetRule rule_;
  int nen_ = 4;
  int nqp_ = 1;
  std::vector<double> values_;
  std::vector<Eigen::Vector3d> gradients_;
  std::vector<double> dv_;
  std::vector<Eigen::Vector3d> positions_;
};

}  // namespace isomuscle::tet
