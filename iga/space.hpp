#pragma once
// The isogeometric space over one NURBS solid (Hughes, Cottrell & Bazilevs 2005): the elements are
// the non-empty knot spans, the shape functions are the rational basis functions R_a of the
// geometry itself (thesis 5.11 in three directions), and everything assembly needs is tabulated
// once, in the REFERENCE configuration, in flat contiguous arrays indexed by (element, point):
//
//   R_a(xi_q)                          basis values
//   dR_a/dX = J^-T dR_a/dxi            reference physical gradients, J = dX/dxi (3x3)
//   dV_q = det J(xi_q) w_q |box_e|/8   reference volume of the quadrature point, m^3
//   J(xi_q), X(xi_q), xi_q             geometry Jacobian (its columns are the isocurve tangents,
//                                      SPEC §1), position and parametric coordinates
//
// Memory: 32 n_el n_qp n_en bytes for values and gradients (p = 2, 27 x 27 per element: 23 KB per
// element); memory_bytes() reports it.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "geometry/gauss_legendre.hpp"
#include "geometry/nurbs_volume.hpp"

namespace isomuscle::iga {

// Largest number of Gauss–Legendre points per direction of an element rule.
inline constexpr int kMaxGaussPoints = 32;

struct QuadratureOptions {
  // Gauss–Legendre points per parametric direction; 0 means p_d + 1 in direction d (exact for the
  // polynomial part of the stiffness of an affine element; the default of Hughes et al. 2005).
  std::array<int, 3> points = {0, 0, 0};
  // Throws std::invalid_argument naming the direction when a count is negative or too large.
  void validate() const;
};

// One knot span: its span indices (as KnotVector::find_span returns them) and parametric box.
struct Element {
  std::array<int, 3> span;
  std::array<int, 3> position;  // (i, j, k) among the non-empty spans of each direction
  std::array<std::array<double, 2>, 3> box;
};

class Space {
 public:
  // Tabulates the basis of `volume` (already refined as wanted). Throws std::invalid_argument when
  // det J <= 0 (or not finite) at a quadrature point, naming the element, the point and the value:
  // a left-handed parametrisation (exchange two parametric directions) or a degenerate solid.
  explicit Space(geometry::NurbsVolume volume, QuadratureOptions options = {});

  const geometry::NurbsVolume& volume() const { return volume_; }
  const QuadratureOptions& quadrature() const { return options_; }

  int num_elements() const { return static_cast<int>(elements_.size()); }
  // Basis functions per element, (p+1)(q+1)(r+1).
  int functions_per_element() const { return nen_; }
  // Quadrature points per element (the tensor rule).
  int points_per_element() const { return nqp_; }
  // Gauss–Legendre points per direction of the tensor rule; point q = qu + nu (qv + nv qw).
  const std::array<int, 3>& points_per_direction() const { return npts_; }
  // The 1D rule of direction d (points_per_direction()[d] points on [-1, 1]), built once here so
  // that per-point queries (quadrature_point_interpolation.hpp) do not rebuild it by Newton
  // iteration on every call.
  const geometry::GaussLegendreRule& rule(int d) const { return rules_[d]; }
  int num_points() const { return num_elements() * nqp_; }
  // Number of non-empty spans per direction.
  const std::array<int, 3>& element_counts() const { return counts_; }

  const Element& element(int e) const { return elements_[e]; }
  // Global control point indices of the element's functions, in the local order a.
  std::span<const int> control_points(int e) const {
    return {connectivity_.data() + static_cast<std::size_t>(e) * nen_,
            static_cast<std::size_t>(nen_)};
  }

  // Tabulated data of point q of element e (flat index e * nqp + q).
  std::span<const double> values(int e, int q) const {
    return {values_.data() + flat(e, q) * nen_, static_cast<std::size_t>(nen_)};
  }
  std::span<const Eigen::Vector3d> gradients(int e, int q) const {
    return {gradients_.data() + flat(e, q) * nen_, static_cast<std::size_t>(nen_)};
  }
  double dv(int e, int q) const { return dv_[flat(e, q)]; }
  // dV of all points of element e.
  std::span<const double> element_dv(int e) const {
    return {dv_.data() + flat(e, 0), static_cast<std::size_t>(nqp_)};
  }
  const Eigen::Matrix3d& jacobian(int e, int q) const { return jacobians_[flat(e, q)]; }
  const Eigen::Vector3d& position(int e, int q) const { return positions_[flat(e, q)]; }
  const Eigen::Vector3d& parametric(int e, int q) const { return parametric_[flat(e, q)]; }

  // Reference volume, the sum of all dV (m^3).
  double reference_volume() const;
  // The element whose (closed) parametric box holds xi; on a boundary between elements the one
  // with the larger span index, at the domain end the last. Throws std::invalid_argument when xi
  // is outside the parametric domain (naming the coordinate).
  int locate(const Eigen::Vector3d& xi) const;

  std::size_t memory_bytes() const;

 private:
  std::size_t flat(int e, int q) const {
    return static_cast<std::size_t>(e) * static_cast<std::size_t>(nqp_) +
           static_cast<std::size_t>(q);
  }

  geometry::NurbsVolume volume_;
  QuadratureOptions options_;
  std::array<int, 3> counts_ = {0, 0, 0};
  std::array<std::vector<int>, 3> span_of_position_;  // non-empty span indices per direction
  int nen_ = 0;
  int nqp_ = 0;
  std::array<int, 3> npts_ = {0, 0, 0};
  std::array<geometry::GaussLegendreRule, 3> rules_;
  std::vector<Element> elements_;
  std::vector<int> connectivity_;
  std::vector<double> values_;
  std::vector<Eigen::Vector3d> gradients_;
  std::vector<double> dv_;
  std::vector<Eigen::Matrix3d> jacobians_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Vector3d> parametric_;
};

}  // namespace isomuscle::iga
