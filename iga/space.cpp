#include "iga/space.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geometry/gauss_legendre.hpp"

namespace isomuscle::iga {

namespace {

const char* kDirection[3] = {"u", "v", "w"};

}  // namespace

void QuadratureOptions::validate() const {
  for (int d = 0; d < 3; ++d) {
    if (points[d] < 0 || points[d] > kMaxGaussPoints) {
      throw std::invalid_argument("quadrature points in direction " + std::string(kDirection[d]) +
                                  " = " + std::to_string(points[d]) +
                                  ": valid are 0 (degree + 1) or 1.." +
                                  std::to_string(kMaxGaussPoints));
    }
  }
}

// Tabulation of the rational basis on the tensor Gauss rule of each knot span (thesis 5.11):
// xi = (a + b)/2 + (b - a)/2 t per direction, dV = det(dX/dxi) prod_d w_d (b_d - a_d)/2, and
// dR/dX = (dX/dxi)^-T dR/dxi with dX/dxi = sum_a X_a (dR_a/dxi)^T.
Space::Space(geometry::NurbsVolume volume, QuadratureOptions options)
    : volume_(std::move(volume)), options_(options) {
  options_.validate();
  std::array<geometry::GaussLegendreRule, 3> rules;
  std::array<int, 3> npts{};
  for (int d = 0; d < 3; ++d) {
    const geometry::KnotVector& kv = volume_.knots(d);
    if (kv.size() == 0) {
      throw std::invalid_argument(
          std::string("iga::Space: the volume has no knot vector in direction ") + kDirection[d]);
    }
    npts[d] = options_.points[d] > 0 ? options_.points[d] : kv.degree() + 1;
    rules[d] = geometry::gauss_legendre_rule(npts[d]);
    for (int i = kv.degree(); i < kv.num_basis(); ++i) {
      if (kv[i] < kv[i + 1]) {
        span_of_position_[d].push_back(i);
      }
    }
    counts_[d] = static_cast<int>(span_of_position_[d].size());
    if (counts_[d] == 0) {
      throw std::invalid_argument(std::string("iga::Space: the knot vector in direction ") +
                                  kDirection[d] + " has no non-empty span");
    }
  }
  nen_ = (volume_.degree(0) + 1) * (volume_.degree(1) + 1) * (volume_.degree(2) + 1);
  npts_ = npts;
  rules_ = rules;
  nqp_ = npts[0] * npts[1] * npts[2];
  const int nel = counts_[0] * counts_[1] * counts_[2];
  const std::size_t npoint = static_cast<std::size_t>(nel) * static_cast<std::size_t>(nqp_);
  elements_.resize(nel);
  connectivity_.resize(static_cast<std::size_t>(nel) * nen_);
  values_.resize(npoint * nen_);
  gradients_.resize(npoint * nen_);
  dv_.resize(npoint);
  jacobians_.resize(npoint);
  positions_.resize(npoint);
  parametric_.resize(npoint);

  const auto& points = volume_.points();
  geometry::VolumeBasis basis;
  for (int k = 0; k < counts_[2]; ++k) {
    for (int j = 0; j < counts_[1]; ++j) {
      for (int i = 0; i < counts_[0]; ++i) {
        const int e = i + counts_[0] * (j + counts_[1] * k);
        Element& el = elements_[e];
        el.position = {i, j, k};
        el.span = {span_of_position_[0][i], span_of_position_[1][j], span_of_position_[2][k]};
        for (int d = 0; d < 3; ++d) {
          const geometry::KnotVector& kv = volume_.knots(d);
          el.box[d] = {kv[el.span[d]], kv[el.span[d] + 1]};
        }
        for (int qw = 0; qw < npts[2]; ++qw) {
          for (int qv = 0; qv < npts[1]; ++qv) {
            for (int qu = 0; qu < npts[0]; ++qu) {
              const int q = qu + npts[0] * (qv + npts[1] * qw);
              const std::array<int, 3> qi = {qu, qv, qw};
              Eigen::Vector3d xi;
              double weight = 1.0;
              for (int d = 0; d < 3; ++d) {
                const double a = el.box[d][0];
                const double b = el.box[d][1];
                xi[d] = 0.5 * (a + b) + 0.5 * (b - a) * rules[d].points[qi[d]];
                weight *= 0.5 * (b - a) * rules[d].weights[qi[d]];
              }
              volume_.evaluate_basis_in_span(el.span, xi, basis);
              if (static_cast<int>(basis.index.size()) != nen_) {
                throw std::logic_error("iga::Space: evaluate_basis_in_span returned " +
                                       std::to_string(basis.index.size()) +
                                       " functions, expected " + std::to_string(nen_));
              }
              int* conn = connectivity_.data() + static_cast<std::size_t>(e) * nen_;
              if (q == 0) {
                std::copy(basis.index.begin(), basis.index.end(), conn);
              } else if (!std::equal(basis.index.begin(), basis.index.end(), conn)) {
                throw std::logic_error("iga::Space: basis indices differ within element " +
                                       std::to_string(e));
              }
              Eigen::Matrix3d jac = Eigen::Matrix3d::Zero();
              Eigen::Vector3d x = Eigen::Vector3d::Zero();
              for (int a = 0; a < nen_; ++a) {
                const Eigen::Vector3d& xa = points[basis.index[a]];
                x.noalias() += basis.value[a] * xa;
                jac.noalias() += xa * basis.derivative[a].transpose();
              }
              const double det = jac.determinant();
              if (!(det > 0.0) || !std::isfinite(det)) {
                std::ostringstream msg;
                msg << "iga::Space: det(dX/dxi) = " << det << " <= 0 at quadrature point " << q
                    << " of element " << e << " (spans " << el.span[0] << ", " << el.span[1] << ", "
                    << el.span[2] << "), xi = (" << xi[0] << ", " << xi[1] << ", " << xi[2]
                    << "), X = (" << x[0] << ", " << x[1] << ", " << x[2]
                    << "): the solid is left-handed (exchange or reverse one parametric "
                       "direction) or degenerate there";
                throw std::invalid_argument(msg.str());
              }
              const Eigen::Matrix3d jinv_t = jac.inverse().transpose();
              const std::size_t f = flat(e, q);
              double* val = values_.data() + f * nen_;
              Eigen::Vector3d* grad = gradients_.data() + f * nen_;
              for (int a = 0; a < nen_; ++a) {
                val[a] = basis.value[a];
                grad[a].noalias() = jinv_t * basis.derivative[a];
              }
              dv_[f] = det * weight;
              jacobians_[f] = jac;
              positions_[f] = x;
              parametric_[f] = xi;
            }
          }
        }
      }
    }
  }
}

double Space::reference_volume() const {
  double v = 0.0;
  for (double d : dv_) {
    v += d;
  }
  return v;
}

int Space::locate(const Eigen::Vector3d& xi) const {
  std::array<int, 3> pos{};
  for (int d = 0; d < 3; ++d) {
    const geometry::KnotVector& kv = volume_.knots(d);
    const double a = kv.domain_begin();
    const double b = kv.domain_end();
    const double tol = 1e-12 * (b - a);
    if (!(xi[d] >= a - tol && xi[d] <= b + tol)) {
      std::ostringstream msg;
      msg << "iga::Space::locate: parametric coordinate " << kDirection[d] << " = " << xi[d]
          << " is outside the domain [" << a << ", " << b << "]";
      throw std::invalid_argument(msg.str());
    }
    const int span = kv.find_span(std::clamp(xi[d], a, b));
    const auto& spans = span_of_position_[d];
    const auto it = std::upper_bound(spans.begin(), spans.end(), span);
    pos[d] = std::max(0, static_cast<int>(it - spans.begin()) - 1);
  }
  return pos[0] + counts_[0] * (pos[1] + counts_[1] * pos[2]);
}

std::size_t Space::memory_bytes() const {
  return values_.size() * sizeof(double) + gradients_.size() * sizeof(Eigen::Vector3d) +
         dv_.size() * sizeof(double) + jacobians_.size() * sizeof(Eigen::Matrix3d) +
         positions_.size() * sizeof(Eigen::Vector3d) +
         parametric_.size() * sizeof(Eigen::Vector3d) + connectivity_.size() * sizeof(int) +
         elements_.size() * sizeof(Element);
}

}  // namespace isomuscle::iga
