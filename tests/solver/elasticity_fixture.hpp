#pragma once
// A 3D linear-elasticity stiffness on the unit cube, for the linear-solver tests and
// bench/bench_cholmod.cpp: n^3 elements of degree 1 (trilinear hexahedra, 8 nodes) or degree 2
// (uniform C^1 quadratic B-splines, 27 control points per element, the IGA pattern), 3 DOFs per
// node, the face z = 0 fixed. K_e = sum_q B^T D B w_q |J| (the displacement element of Hughes, The
// Finite Element Method, ch. 3; isotropic D with E = 1, nu = 0.3), (p + 1)^3 Gauss points, the
// same for every element of the uniform grid. The matrix is symmetric positive definite.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "solver/element_dofs.hpp"
#include "solver/sparsity_pattern.hpp"

namespace isomuscle::solver::testing {

struct ElasticityGrid {
  int n = 0;       // elements per side
  int degree = 1;  // 1 or 2
  int nodes_per_side() const { return n + degree; }
  int nodes_per_element() const { return (degree + 1) * (degree + 1) * (degree + 1); }
};

// 1D basis on an element of the uniform grid, local coordinate t in [0, 1]: the degree-1 Lagrange
// pieces or the three pieces of the uniform quadratic B-spline (Piegl & Tiller eq. 2.5).
inline void basis_1d(int degree, double t, std::array<double, 3>& value,
                     std::array<double, 3>& derivative) {
  if (degree == 1) {
    value = {1.0 - t, t, 0.0};
    derivative = {-1.0, 1.0, 0.0};
  } else {
    value = {0.5 * (1.0 - t) * (1.0 - t), 0.5 * (1.0 + 2.0 * t - 2.0 * t * t), 0.5 * t * t};
    derivative = {-(1.0 - t), 1.0 - 2.0 * t, t};
  }
}

// Element stiffness of an element of size h = 1 / n (N/m with E = 1 Pa, unit lengths).
inline Eigen::MatrixXd element_stiffness(const ElasticityGrid& grid) {
  const int p = grid.degree;
  const int m = p + 1;
  const int n_nodes = grid.nodes_per_element();
  const double h = 1.0 / grid.n;
  const double young = 1.0;
  const double nu = 0.3;
  const double lambda = young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = young / (2.0 * (1.0 + nu));
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(lambda);
  d.diagonal().head<3>().array() += 2.0 * mu;
  d.diagonal().tail<3>().setConstant(mu);
  // Gauss–Legendre points on [0, 1].
  std::vector<double> points;
  std::vector<double> weights;
  if (m == 2) {
    const double a = 0.5 / std::sqrt(3.0);
    points = {0.5 - a, 0.5 + a};
    weights = {0.5, 0.5};
  } else {
    const double a = 0.5 * std::sqrt(0.6);
    points = {0.5 - a, 0.5, 0.5 + a};
    weights = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  }
  Eigen::MatrixXd ke = Eigen::MatrixXd::Zero(3 * n_nodes, 3 * n_nodes);
  Eigen::MatrixXd b(6, 3 * n_nodes);
  std::array<std::array<double, 3>, 3> value{};
  std::array<std::array<double, 3>, 3> derivative{};
  for (int qz = 0; qz < m; ++qz) {
    for (int qy = 0; qy < m; ++qy) {
      for (int qx = 0; qx < m; ++qx) {
        basis_1d(p, points[qx], value[0], derivative[0]);
        basis_1d(p, points[qy], value[1], derivative[1]);
        basis_1d(p, points[qz], value[2], derivative[2]);
        b.setZero();
        int a = 0;
        for (int k = 0; k < m; ++k) {
          for (int j = 0; j < m; ++j) {
            for (int i = 0; i < m; ++i, ++a) {
              const double gx = derivative[0][i] * value[1][j] * value[2][k] / h;
              const double gy = value[0][i] * derivative[1][j] * value[2][k] / h;
              const double gz = value[0][i] * value[1][j] * derivative[2][k] / h;
              // Voigt order xx, yy, zz, yz, xz, xy (engineering shear strains).
              b(0, 3 * a) = gx;
              b(1, 3 * a + 1) = gy;
              b(2, 3 * a + 2) = gz;
              b(3, 3 * a + 1) = gz;
              b(3, 3 * a + 2) = gy;
              b(4, 3 * a) = gz;
              b(4, 3 * a + 2) = gx;
              b(5, 3 * a) = gy;
              b(5, 3 * a + 1) = gx;
            }
          }
        }
        const double w = weights[qx] * weights[qy] * weights[qz] * h * h * h;
        ke.noalias() += w * (b.transpose() * d * b);
      }
    }
  }
  return ke;
}

// Free-DOF lists of the grid's elements (nodes with z index 0 prescribed), and the number of free
// DOFs through n_free.
inline ElementDofs elasticity_dofs(const ElasticityGrid& grid, int& n_free) {
  const int s = grid.nodes_per_side();
  std::vector<int> node_dof(static_cast<std::size_t>(s) * s * s, -1);
  n_free = 0;
  for (int k = 1; k < s; ++k) {
    for (int j = 0; j < s; ++j) {
      for (int i = 0; i < s; ++i) {
        node_dof[(static_cast<std::size_t>(k) * s + j) * s + i] = n_free;
        n_free += 3;
      }
    }
  }
  const int m = grid.degree + 1;
  ElementDofs elements;
  std::vector<int> dofs(3 * static_cast<std::size_t>(grid.nodes_per_element()));
  for (int ez = 0; ez < grid.n; ++ez) {
    for (int ey = 0; ey < grid.n; ++ey) {
      for (int ex = 0; ex < grid.n; ++ex) {
        int a = 0;
        for (int k = 0; k < m; ++k) {
          for (int j = 0; j < m; ++j) {
            for (int i = 0; i < m; ++i, ++a) {
              const int node =
                  node_dof[(static_cast<std::size_t>(ez + k) * s + ey + j) * s + ex + i];
              for (int c = 0; c < 3; ++c) {
                dofs[3 * a + c] = node < 0 ? kPrescribed : node + c;
              }
            }
          }
        }
        elements.add_element(dofs);
      }
    }
  }
  return elements;
}

struct ElasticitySystem {
  SparsityPattern pattern;
  SparseMatrix stiffness;
};

// The assembled stiffness (serial loop over elements, scatter map).
inline ElasticitySystem make_elasticity(const ElasticityGrid& grid,
                                        MatrixStorage storage = MatrixStorage::Upper) {
  int n_free = 0;
  ElementDofs elements = elasticity_dofs(grid, n_free);
  ElasticitySystem system{SparsityPattern(std::move(elements), n_free, storage), {}};
  system.stiffness = system.pattern.make_matrix();
  const Eigen::MatrixXd ke = element_stiffness(grid);
  for (int e = 0; e < system.pattern.elements().n_elements(); ++e) {
    system.pattern.add_element_matrix(e, ke, system.stiffness);
  }
  return system;
}

// K - sigma I in place (K stored as its upper triangle or in full, with every diagonal entry
// present): symmetric indefinite once sigma exceeds K's smallest eigenvalue, as a tangent past a
// limit point.
inline void shift_diagonal(SparseMatrix& k, double sigma) {
  for (int j = 0; j < k.cols(); ++j) {
    k.coeffRef(j, j) -= sigma;
  }
}

// K - fraction mean(diag K) I, a copy: the indefinite tangents of the solver tests and benchmarks
// (fraction 0.02 and 0.5 put sigma above the smallest eigenvalue of the elasticity grids).
inline SparseMatrix below_mean_diagonal(const SparseMatrix& k, double fraction) {
  SparseMatrix shifted = k;
  shift_diagonal(shifted, fraction * k.diagonal().mean());
  return shifted;
}

}  // namespace isomuscle::solver::testing
