// Volume of a NURBS solid by quadrature of det J and by the divergence theorem; det J sampling.
#include "geometry/volume_measures.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace isomuscle::geometry {

namespace {

void check_points(int n, const char* what) {
  if (n < 1 || n > kMaxGaussLegendrePoints) {
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(n) +
                                " points per direction; use 1.." +
                                std::to_string(kMaxGaussLegendrePoints));
  }
}

// Breakpoints of direction d: the knot spans [b_e, b_{e+1}] are the elements.
std::array<std::vector<double>, 3> all_breakpoints(const NurbsVolume& volume) {
  return {volume.knots(0).breakpoints(), volume.knots(1).breakpoints(),
          volume.knots(2).breakpoints()};
}

// The n-point Gauss–Legendre rule (after checking n for `what`) and the breakpoints of the three
// parametric directions: what both volume integrals loop over.
struct SpanQuadrature {
  GaussLegendreRule rule;
  std::array<std::vector<double>, 3> breaks;
};
SpanQuadrature span_quadrature(const NurbsVolume& volume, int n, const char* what) {
  check_points(n, what);
  return {gauss_legendre_rule(n), all_breakpoints(volume)};
}

}  // namespace

// V = sum over spans and Gauss points of det J(xi) * |span| / 8 * w_a w_b w_c (thesis 5.13 map).
double solid_volume(const NurbsVolume& volume, int points_per_direction) {
  const auto [rule, breaks] = span_quadrature(volume, points_per_direction, "solid_volume");
  const int n = points_per_direction;
  double total = 0.0;
  Eigen::Vector3d point;
  Eigen::Matrix3d jacobian;
  for (std::size_t e2 = 0; e2 + 1 < breaks[2].size(); ++e2) {
    const double a2 = breaks[2][e2];
    const double h2 = breaks[2][e2 + 1] - a2;
    for (std::size_t e1 = 0; e1 + 1 < breaks[1].size(); ++e1) {
      const double a1 = breaks[1][e1];
      const double h1 = breaks[1][e1 + 1] - a1;
      for (std::size_t e0 = 0; e0 + 1 < breaks[0].size(); ++e0) {
        const double a0 = breaks[0][e0];
        const double h0 = breaks[0][e0 + 1] - a0;
        double element = 0.0;
        for (int c = 0; c < n; ++c) {
          for (int b = 0; b < n; ++b) {
            for (int a = 0; a < n; ++a) {
              const Eigen::Vector3d xi(a0 + 0.5 * h0 * (rule.points[a] + 1.0),
                                       a1 + 0.5 * h1 * (rule.points[b] + 1.0),
                                       a2 + 0.5 * h2 * (rule.points[c] + 1.0));
              volume.evaluate_with_jacobian(xi, point, jacobian);
              element +=
                  rule.weights[a] * rule.weights[b] * rule.weights[c] * jacobian.determinant();
            }
          }
        }
        total += element * 0.125 * h0 * h1 * h2;
      }
    }
  }
  return total;
}

// Divergence theorem on the parametric box: det J = div_xi(cof(J)^T H) / 3 (Piola identity), so
// V = 1/3 sum_faces (+/-) integral of H . (H_{d+1} x H_{d+2}) over the face xi_d = const, with
// (d, d+1, d+2) cyclic and + on the face at the end of the domain.
double solid_volume_from_boundary(const NurbsVolume& volume, int points_per_direction) {
  const auto [rule, breaks] =
      span_quadrature(volume, points_per_direction, "solid_volume_from_boundary");
  const int n = points_per_direction;
  double total = 0.0;
  Eigen::Vector3d point;
  Eigen::Matrix3d jacobian;
  for (int d = 0; d < 3; ++d) {
    const int d1 = (d + 1) % 3;
    const int d2 = (d + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      const double fixed = side == 0 ? breaks[d].front() : breaks[d].back();
      const double sign = side == 0 ? -1.0 : 1.0;
      for (std::size_t e2 = 0; e2 + 1 < breaks[d2].size(); ++e2) {
        const double a2 = breaks[d2][e2];
        const double h2 = breaks[d2][e2 + 1] - a2;
        for (std::size_t e1 = 0; e1 + 1 < breaks[d1].size(); ++e1) {
          const double a1 = breaks[d1][e1];
          const double h1 = breaks[d1][e1 + 1] - a1;
          double face = 0.0;
          for (int b = 0; b < n; ++b) {
            for (int a = 0; a < n; ++a) {
              Eigen::Vector3d xi;
              xi[d] = fixed;
              xi[d1] = a1 + 0.5 * h1 * (rule.points[a] + 1.0);
              xi[d2] = a2 + 0.5 * h2 * (rule.points[b] + 1.0);
              volume.evaluate_with_jacobian(xi, point, jacobian);
              const Eigen::Vector3d area = jacobian.col(d1).cross(jacobian.col(d2));
              face += rule.weights[a] * rule.weights[b] * point.dot(area);
            }
          }
          total += sign * face * 0.25 * h1 * h2;
        }
      }
    }
  }
  return total / 3.0;
}

VolumeEstimate converged_solid_volume(const NurbsVolume& volume, double relative_tolerance,
                                      int max_points) {
  check_points(max_points, "converged_solid_volume");
  int n = std::max({volume.degree(0), volume.degree(1), volume.degree(2)}) + 2;
  VolumeEstimate estimate{solid_volume(volume, std::min(n, max_points)), std::min(n, max_points),
                          std::numeric_limits<double>::infinity()};
  while (n + 2 <= max_points) {
    n += 2;
    const double next = solid_volume(volume, n);
    estimate.relative_change = std::abs(next - estimate.volume) / std::abs(next);
    estimate.volume = next;
    estimate.points_per_direction = n;
    if (estimate.relative_change <= relative_tolerance)
      break;
  }
  return estimate;
}

void for_each_cell_sample(const NurbsVolume& volume, int samples_per_span, const char* what,
                          const CellSampleVisitor& visit) {
  if (samples_per_span < 1 || samples_per_span > 100) {
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(samples_per_span) +
                                " samples per span; use 1..100");
  }
  const auto breaks = all_breakpoints(volume);
  const int s = samples_per_span;
  Eigen::Vector3d point;
  Eigen::Matrix3d jacobian;
  for (std::size_t e2 = 0; e2 + 1 < breaks[2].size(); ++e2) {
    for (std::size_t e1 = 0; e1 + 1 < breaks[1].size(); ++e1) {
      for (std::size_t e0 = 0; e0 + 1 < breaks[0].size(); ++e0) {
        const double cell = (breaks[0][e0 + 1] - breaks[0][e0]) *
                            (breaks[1][e1 + 1] - breaks[1][e1]) *
                            (breaks[2][e2 + 1] - breaks[2][e2]) / (s * s * s);
        for (int c = 0; c < s; ++c) {
          for (int b = 0; b < s; ++b) {
            for (int a = 0; a < s; ++a) {
              const auto at = [&](const std::vector<double>& bp, std::size_t e, int k) {
                return bp[e] + (bp[e + 1] - bp[e]) * (k + 0.5) / s;
              };
              const Eigen::Vector3d xi(at(breaks[0], e0, a), at(breaks[1], e1, b),
                                       at(breaks[2], e2, c));
              volume.evaluate_with_jacobian(xi, point, jacobian);
              visit(xi, jacobian, cell);
            }
          }
        }
      }
    }
  }
}

JacobianRange jacobian_range(const NurbsVolume& volume, int samples_per_span) {
  JacobianRange range;
  range.min = std::numeric_limits<double>::infinity();
  range.max = -std::numeric_limits<double>::infinity();
  for_each_cell_sample(volume, samples_per_span, "jacobian_range",
                       [&](const Eigen::Vector3d& xi, const Eigen::Matrix3d& jacobian, double) {
                         const double det = jacobian.determinant();
                         ++range.samples;
                         if (!(det > 0.0))
                           ++range.non_positive;
                         if (det < range.min) {
                           range.min = det;
                           range.argmin = xi;
                         }
                         if (det > range.max) {
                           range.max = det;
                           range.argmax = xi;
                         }
                       });
  return range;
}

}  // namespace isomuscle::geometry
