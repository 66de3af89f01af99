#pragma once
// Lagrange tetrahedra on the reference tetrahedron {xi >= 0, eta >= 0, zeta >= 0,
// xi + eta + zeta <= 1} (volume 1/6) and quadrature rules on it (Zienkiewicz, Taylor & Zhu 2013,
// §6.5; Keast 1986 for the 5-point rule; Stroud 1971 conical product for higher degrees).
// Barycentric coordinates L0 = 1 - xi - eta - zeta, L1 = xi, L2 = eta, L3 = zeta.
//   4 nodes:  N_i = L_i.
//  10 nodes:  N_i = L_i (2 L_i - 1) at the corners, N = 4 L_i L_j at the edge nodes, in gmsh's
//             order 4 (0-1), 5 (1-2), 6 (2-0), 7 (3-0), 8 (3-2), 9 (3-1).
#include <Eigen/Core>
#include <vector>

namespace isomuscle::tet {

// Quadrature on the reference tetrahedron: sum_q w_q f(xi_q) ~ int f (weights sum to 1/6).
struct TetRule {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  int degree = 0;  // polynomials up to this total degree are integrated exactly
};

// The rule exact to total degree `degree` with the fewest points offered here:
//   1 -> 1 point (centroid); 2 -> 4 points (symmetric, positive weights);
//   3 -> 5 points (Keast: one NEGATIVE weight, -2/15; offered for the exactness check only, a
//        material history at a negative-weight point is not a sound energy);
//   4, 5 -> 14 points (symmetric, positive weights, exact to degree 5);
//   6..15 -> conical product of Gauss–Legendre rules (n = ceil((degree + 3)/2)
//        points per direction, positive weights).
// Throws std::invalid_argument outside 1..15.
TetRule tet_rule(int degree);

// The rule a discretisation uses by default: 1 point for 4-node (constant strain), 4 points for
// 10-node tetrahedra (degree 2: exact for the stiffness of a straight-sided element).
TetRule default_tet_rule(int order);

// The rule a run integrates with: default_tet_rule(order) for quadrature_degree 0, else
// tet_rule(quadrature_degree) ([tetrahedra] quadrature_degree). One place, so that the space and
// the folded-element repair look at the same points.
TetRule analysis_tet_rule(int order, int quadrature_degree);

// Shape function values N (4 or 10 entries) at xi.
void tet_shape_values(int order, const Eigen::Vector3d& xi, double* values);
// Gradients dN/dxi (4 or 10 vectors) at xi.
void tet_shape_gradients(int order, const Eigen::Vector3d& xi, Eigen::Vector3d* gradients);

// Nodes of a tetrahedron and triangle per order; throws std::invalid_argument unless order is 1, 2.
int tet_nodes(int order);

}  // namespace isomuscle::tet
