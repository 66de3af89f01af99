// Volume of a NURBS solid by quadrature of det J and by the divergence theorem; det J sampling.
#include "geometry/volume_measures.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace isomuscle::geometry {

namespace {

void check_points(int n, const char* what) {
  if (n < 1 || n > 64) {
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(n) +
                                " points per direction; use 1..64");
  }
}

// Breakpoints of direction d: the knot spans [b_e, b_{e+1}] are the elements.
std::array<std::vector<double>, 3> all_breakpoints(const NurbsVolume& volume) {
  return {volume.knots(0).breakpoints(), volume.knots(1).breakpoints(),
          volume.knots(2).breakpoints()};
}

}  // namespace

// Abramowitz & Stegun 25.4.29: nodes are the roots of P_n, weights 2 / ((1 - x^2) P_n'(x)^2).
// Newton from x0 = cos(pi (i + 3/4) / (n + 1/2)); the recurrence
// (k + 1) P_{k+1} = (2k + 1) x P_k - k P_{k-1} gives P_n and P_n' = n (x P_n - P_{n-1}) / (x^2 -
// 1).
GaussLegendreRule gauss_legendre_rule(int n) {
  check_points(n, "gauss_legendre_rule");
  GaussLegendreRule rule;
  rule.points.resize(static_cast<std::size_t>(n));
  rule.weights.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0;
      double p1 = x;
      for (int k = 1; k < n; ++k) {
        const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);  // p1 = P_n(x), p0 = P_{n-1}(x)
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) <= 1e-16)
        break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.points[static_cast<std::size_t>(i)] = -x;
    rule.points[static_cast<std::size_t>(n - 1 - i)] = x;
    rule.weights[static_cast<std::size_t>(i)] = w;
    rule.weights[static_cast<std::size_t>(n - 1 - i)] = w;
  }
  if (n % 2 == 1)
    rule.points[static_cast<std::size_t>(n / 2)] = 0.0;
  return rule;
}

// V = sum over spans and Gauss points of det J(xi) * |span| / 8 * w_a w_b w_c (thesis 5.13 map).
double solid_volume(const NurbsVolume& volume, int points_per_direction) {
  check_points(points_per_direction, "solid_volume");
  const GaussLegendreRule rule = gauss_legendre_rule(points_per_direction);
  const auto breaks = all_breakpoints(volume);
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
  check_points(points_per_direction, "solid_volume_from_boundary");
  const GaussLegendreRule rule = gauss_legendre_rule(points_per_direction);
  const auto breaks = all_breakpoints(volume);
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

JacobianRange jacobian_range(const NurbsVolume& volume, int samples_per_span) {
  if (samples_per_span < 1 || samples_per_span > 100) {
    throw std::invalid_argument("jacobian_range: " + std::to_string(samples_per_span) +
                                " samples per span; use 1..100");
  }
  const auto breaks = all_breakpoints(volume);
  const int s = samples_per_span;
  JacobianRange range;
  range.min = std::numeric_limits<double>::infinity();
  range.max = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d point;
  Eigen::Matrix3d jacobian;
  for (std::size_t e2 = 0; e2 + 1 < breaks[2].size(); ++e2) {
    for (std::size_t e1 = 0; e1 + 1 < breaks[1].size(); ++e1) {
      for (std::size_t e0 = 0; e0 + 1 < breaks[0].size(); ++e0) {
        for (int c = 0; c < s; ++c) {
          for (int b = 0; b < s; ++b) {
            for (int a = 0; a < s; ++a) {
              const auto at = [&](const std::vector<double>& bp, std::size_t e, int k) {
                return bp[e] + (bp[e + 1] - bp[e]) * (k + 0.5) / s;
              };
              const Eigen::Vector3d xi(at(breaks[0], e0, a), at(breaks[1], e1, b),
                                       at(breaks[2], e2, c));
              volume.evaluate_with_jacobian(xi, point, jacobian);
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
            }
          }
        }
      }
    }
  }
  return range;
}

}  // namespace isomuscle::geometry
