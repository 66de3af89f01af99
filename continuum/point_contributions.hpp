#pragma once
// Quadrature-point contributions of the total Lagrangian formulation (Bonet & Wood 2008, 8.3;
// Holzapfel 2000 §8.4), shared by every element kernel: the deformation gradient from the element
// displacements, the internal force P dN_a/dX dV, the material stiffness B^T C B dV and the
// geometric (initial stress) stiffness (dN_a/dX . S dN_b/dX) I dV. The tangent is accumulated in
// its upper triangle only (K_e is symmetric), over groups of points in one product, and mirrored
// once per element by finish_tangent.
#include <Eigen/Core>
#include <span>

#include "continuum/element_workspace.hpp"
#include "materials/material_law.hpp"

namespace isomuscle::continuum {

using Matrix3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;
using ConstMap3X = Eigen::Map<const Matrix3X>;

// dN/dX of all functions at point q, 3 x nen (1/m).
ConstMap3X gradient_matrix(const ElementView& el, int q);

// F = I + sum_a u_a (x) dN_a/dX (Bonet & Wood 2008, 8.3), dimensionless.
Eigen::Matrix3d deformation_gradient(const Matrix3X& ue, const ConstMap3X& grad);

// Voigt strain-displacement matrix of dE = sym(F^T dF), order 11, 22, 33, 2·12, 2·23, 2·13
// (Bonet & Wood 2008, 8.3): columns 3a + k, 1/m.
void fill_b(const Eigen::Matrix3d& F, const ConstMap3X& grad,
            Eigen::Matrix<double, 6, Eigen::Dynamic>& B);

// The stiffness sums over the points are taken kPointsPerProduct points at a time, one product
// each: one point alone gives products of inner dimension 6 (B^T C B) and 3 (H), which read and
// write the whole n x n upper triangle per point; all points of a degree-4 element at once no
// longer fit in cache (bench/bench_iga, BM_ElementResidualTangent).
inline constexpr int kPointsPerProduct = 8;

// Point q (the points in order 0, 1, ...): f_a += F S dN_a/dX dV (N); with C (Pa), its factors
// B, C B dV, dN/dX and S dN/dX dV of the stiffness, kept in the workspace and added to the upper
// triangles of K (B^T C B dV) and H (dN/dX . S dN/dX dV) for every kPointsPerProduct points.
void add_point(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S, const materials::Matrix6d* C,
               const ConstMap3X& grad, double dv, int q, ElementWorkspace& ws);

// After the last point (nqp points given C): adds the points not yet added (N/m).
void add_point_stiffness(ElementWorkspace& ws, int nqp);

// K(3a + i, 3b + i) += H(a, b) for a <= b: the geometric stiffness, upper part.
void add_geometric(ElementWorkspace& ws, int nen);

// The lower triangle of K_e from the upper one (K_e is symmetric).
void finish_tangent(ElementWorkspace& ws);

// Points the material input/output at point q's committed and trial history (history_size hs),
// and passes on whether the trial history is current.
void bind_history(const MaterialContext& mat, int q, int hs, materials::PointInput& in,
                  materials::PointResult& out);

}  // namespace isomuscle::continuum
