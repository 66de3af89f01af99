#pragma once
// Geometries and helpers shared by the iga tests: exact NURBS solids built here or with geometry/
// (shapes + shrink), refined with geometry/refinement, and a Newton driver on solver::NewtonSolver.
#include <Eigen/Core>
#include <array>
#include <functional>

#include "geometry/nurbs_volume.hpp"
#include "iga/problem.hpp"
#include "solver/newton.hpp"

namespace isomuscle::iga::testing {

// Axis-aligned box [0, a] x [0, b] x [0, c] of degrees p and n elements per direction (trilinear
// map elevated and refined: the parametrisation stays affine).
geometry::NurbsVolume box(const Eigen::Vector3d& size, const std::array<int, 3>& degree,
                          const std::array<int, 3>& elements);
// The unit cube of degree p, n elements per direction, with every control point moved by a random
// vector of length up to `amplitude` times the smallest control-point spacing and every weight set
// to a random value in [0.7, 1.3] (deterministic seed): a distorted rational block. rational =
// false keeps all weights 1 (a distorted B-spline block, polynomial map).
geometry::NurbsVolume distorted_rational_block(int p, int n, double amplitude, unsigned seed,
                                               bool rational = true);
// Shrink solid of a circular cylinder (radius, height) built from the rational nine-point circle
// surface (geometry::cone_frustum with equal radii) by geometry::shrink_to_centreline: closed seam
// at u = 0/1, collapsed axis at w = 1. Degrees raised to at least p, n_per_span knots inserted per
// span in (around, along, radial).
geometry::NurbsVolume shrink_cylinder(double radius, double height, int p,
                                      const std::array<int, 3>& n_per_span);
// The same shrink solid built from a POLYNOMIAL closed surface: the circle replaced by a clamped
// quadratic B-spline whose control points are a regular octagon (the first repeated last, all
// weights 1), so the solid is a polynomial map with the same seam and collapsed axis.
geometry::NurbsVolume polynomial_shrink_cylinder(double radius, double height, int p,
                                                 const std::array<int, 3>& n_per_span);
// Shrink solid of the barrel (geometry::barrel, SPEC §5 dimensions unless given).
geometry::NurbsVolume shrink_barrel(int p, const std::array<int, 3>& n_per_span);
// Annular sector r in [r0, r1], theta in [0, angle] (angle <= pi/2, one rational quadratic arc
// with middle weight cos(angle/2)), z in [0, h]; u radial (degree 1 -> p), v around (-> max(p, 2)),
// w along z (degree 1 -> p); n elements per direction in the plane (u, v), nz along z.
geometry::NurbsVolume annular_sector(double r0, double r1, double h, double angle, int p, int n,
                                     int nz);
// Cook's membrane: the bilinear trapezoid (0,0), (48,44), (48,60), (0,44) (u along x, v up),
// extruded to thickness t in z; degree p, (nu, nv, nw) elements.
geometry::NurbsVolume cook_membrane(int p, int nu, int nv, int nw, double thickness);

// Newton settings for tight verification solves.
solver::NewtonSettings tight_newton(double rtol = 1e-12);

// Runs steps t_k = k / steps (k = 1..steps) with Newton; returns false (and message) on failure.
bool solve_steps(solver::NonlinearProblem& problem, Eigen::VectorXd& u, int steps,
                 const solver::NewtonSettings& settings, std::string* message = nullptr,
                 std::vector<solver::NewtonResult>* results = nullptr);

}  // namespace isomuscle::iga::testing
