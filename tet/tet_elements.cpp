#include "tet/tet_elements.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "geometry/gauss_legendre.hpp"

namespace isomuscle::tet {

namespace {

// Conical product rule (Stroud 1971, §2.7): the cube [0,1]^3 mapped onto the tetrahedron by
// xi = u, eta = v (1 - u), zeta = w (1 - u)(1 - v), det = (1 - u)^2 (1 - v); n Gauss–Legendre
// points per direction integrate x^a (1 - u)^(a+2) ... exactly up to total degree 2n - 3.
TetRule conical_rule(int n, int degree) {
  const geometry::GaussLegendreRule g = geometry::gauss_legendre_rule(n);
  TetRule rule;
  rule.degree = degree;
  for (int i = 0; i < n; ++i) {
    const double u = 0.5 * (g.points[i] + 1.0);
    for (int j = 0; j < n; ++j) {
      const double v = 0.5 * (g.points[j] + 1.0);
      for (int k = 0; k < n; ++k) {
        const double w = 0.5 * (g.points[k] + 1.0);
        rule.points.emplace_back(u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v));
        rule.weights.push_back(0.125 * g.weights[i] * g.weights[j] * g.weights[k] * (1.0 - u) *
                               (1.0 - u) * (1.0 - v));
      }
    }
  }
  return rule;
}

// The symmetric 14-point rule of degree 5 with positive weights (the degree-5 tetrahedron rule of
// Witherden & Vincent 2015, among others): 4 points at (a, a, a, 1 - 3a) in
// barycentric coordinates for each of two a, and 6 at (b, b, 1/2 - b, 1/2 - b). The constants
// solve the symmetric moment equations to machine precision (checked by the monomial test); at
// degree 4 the conical product would need 64 points.
TetRule symmetric_14_point_rule(int degree) {
  struct Orbit {
    double a, weight;
  };
  const Orbit vertex_orbits[2] = {{0.092735250310890055, 0.012248840519393294},
                                  {0.31088591926330023, 0.018781320953001723}};
  const double b = 0.045503704125655436, edge_weight = 0.0070910034628477552;
  TetRule rule;
  rule.degree = degree;
  for (const Orbit& o : vertex_orbits) {
    const double c = 1.0 - 3.0 * o.a;
    // (L1, L2, L3) with L0 = 1 - L1 - L2 - L3: the odd coordinate at each of the four vertices.
    rule.points.insert(rule.points.end(),
                       {{o.a, o.a, o.a}, {c, o.a, o.a}, {o.a, c, o.a}, {o.a, o.a, c}});
    rule.weights.insert(rule.weights.end(), 4, o.weight);
  }
  // The two coordinates equal to b on each of the six edges {i, j} of (L0, L1, L2, L3).
  const double h = 0.5 - b;
  rule.points.insert(rule.points.end(),
                     {{b, h, h}, {h, b, h}, {h, h, b}, {b, b, h}, {b, h, b}, {h, b, b}});
  rule.weights.insert(rule.weights.end(), 6, edge_weight);
  return rule;
}

}  // namespace

int tet_nodes(int order) {
  if (order == 1) {
    return 4;
  }
  if (order == 2) {
    return 10;
  }
  throw std::invalid_argument("tetrahedron order " + std::to_string(order) +
                              " is not supported (valid: 1 = 4-node, 2 = 10-node)");
}

// Rules on the reference tetrahedron of volume 1/6 (header).
TetRule tet_rule(int degree) {
  TetRule rule;
  rule.degree = degree;
  if (degree == 1) {
    rule.points.emplace_back(0.25, 0.25, 0.25);
    rule.weights.push_back(1.0 / 6.0);
    return rule;
  }
  if (degree == 2) {
    // a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20, weights 1/24.
    const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0;
    const double b = (5.0 - std::sqrt(5.0)) / 20.0;
    rule.points = {{b, b, b}, {a, b, b}, {b, a, b}, {b, b, a}};
    rule.weights.assign(4, 1.0 / 24.0);
    return rule;
  }
  if (degree == 3) {
    // Keast #2: centroid -4/30, four points (1/2, 1/6, 1/6, 1/6) with 9/120 (volume 1/6).
    const double s = 1.0 / 6.0;
    rule.points = {{0.25, 0.25, 0.25}, {s, s, s}, {0.5, s, s}, {s, 0.5, s}, {s, s, 0.5}};
    rule.weights = {-4.0 / 30.0, 9.0 / 120.0, 9.0 / 120.0, 9.0 / 120.0, 9.0 / 120.0};
    return rule;
  }
  if (degree == 4 || degree == 5) {
    return symmetric_14_point_rule(degree);
  }
  if (degree >= 6 && degree <= 15) {
    return conical_rule((degree + 4) / 2, degree);
  }
  throw std::invalid_argument("tetrahedron quadrature degree " + std::to_string(degree) +
                              " is not offered (valid: 1 to 15)");
}

TetRule default_tet_rule(int order) {
  return tet_rule(tet_nodes(order) == 4 ? 1 : 2);
}

TetRule analysis_tet_rule(int order, int quadrature_degree) {
  return quadrature_degree == 0 ? default_tet_rule(order) : tet_rule(quadrature_degree);
}

// N_i = L_i (4 nodes); L_i (2 L_i - 1) and 4 L_i L_j (10 nodes), header.
void tet_shape_values(int order, const Eigen::Vector3d& xi, double* values) {
  const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  if (tet_nodes(order) == 4) {
    for (int i = 0; i < 4; ++i) {
      values[i] = L[i];
    }
    return;
  }
  for (int i = 0; i < 4; ++i) {
    values[i] = L[i] * (2.0 * L[i] - 1.0);
  }
  values[4] = 4.0 * L[0] * L[1];
  values[5] = 4.0 * L[1] * L[2];
  values[6] = 4.0 * L[2] * L[0];
  values[7] = 4.0 * L[3] * L[0];
  values[8] = 4.0 * L[3] * L[2];
  values[9] = 4.0 * L[3] * L[1];
}

// dN/dxi by the chain rule through dL/dxi (header).
void tet_shape_gradients(int order, const Eigen::Vector3d& xi, Eigen::Vector3d* gradients) {
  const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  const Eigen::Vector3d dL[4] = {Eigen::Vector3d(-1.0, -1.0, -1.0), Eigen::Vector3d::UnitX(),
                                 Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  if (tet_nodes(order) == 4) {
    for (int i = 0; i < 4; ++i) {
      gradients[i] = dL[i];
    }
    return;
  }
  for (int i = 0; i < 4; ++i) {
    gradients[i] = (4.0 * L[i] - 1.0) * dL[i];
  }
  constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  for (int k = 0; k < 6; ++k) {
    const int i = kEdges[k][0];
    const int j = kEdges[k][1];
    gradients[4 + k] = 4.0 * (L[i] * dL[j] + L[j] * dL[i]);
  }
}

}  // namespace isomuscle::tet
