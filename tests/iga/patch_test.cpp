// Patch test: an affine displacement u = t (F0 - I) X prescribed at every boundary control point
// is reproduced at every quadrature point (F = F0, S = S(F0)) after the Newton solve, both
// formulations, p = 1..4.
//
// For NURBS the affine field lies in the space exactly (sum R_a = 1, sum R_a X_a = X), so F = F0
// holds pointwise as soon as the affine field IS the discrete solution, i.e. when its discrete
// equilibrium sum_q P0 dR_a/dX dV_q = P0 sum_q cof(dX/dxi)^T dR_a/dxi w_q = 0 holds for every
// interior function a. The exact integral vanishes (divergence theorem); the quadrature sum does
// when the rule integrates cof(dX/dxi)^T dR_a/dxi exactly:
//  * polynomial (B-spline) maps of degree p: the integrand has degree 3p - 1 per direction, so
//    ceil(3p/2) Gauss points per direction are exact (p + 1 suffices for p <= 2): asserted 1e-10;
//  * rational maps (weights != 1, the rational circle of the shrink cylinder): the integrand is
//    rational and no Gauss rule is exact; the defect is pure quadrature error, shown by its fast
//    decay with the number of points (measured and asserted below). Reaching 1e-10 there needs
//    about p + 10 points per direction (measured: p + 5 gives 1e-6 to 1e-9), too slow for a unit
//    test; a variationally consistent integration (Hillman, Chen & Bazilevs 2015) would remove
//    the defect at any quadrature but makes the Galerkin tangent non-symmetric.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::iga {
namespace {

struct PatchErrors {
  double F = 0.0;      // max |F_h - F0| (entries) over the quadrature points
  double S = 0.0;      // max |S_h - S0| / |S0|
  double min_J = 0.0;  // |smallest J of the committed state - det F0|
  double max_J = 0.0;  // |largest J of the committed state - det F0|
  int iterations = 0;
};

Eigen::Matrix3d affine_gradient() {
  Eigen::Matrix3d F0;      // 10 % stretch, 5 % compression, shears
  F0 << 1.10, 0.05, 0.02,  //
      0.03, 0.95, 0.04,    //
      -0.02, 0.06, 1.05;
  return F0;
}

PatchErrors run_patch(const geometry::NurbsVolume& vol, const std::vector<Side>& sides,
                      Formulation formulation, int points) {
  QuadratureOptions quad;
  quad.points = {points, points, points};
  const Space space(vol, quad);
  const DofMap dofs(vol);
  const auto law = materials::make_material("neo_hookean", {{"C10", 0.5}, {"K", 100.0}});
  const Eigen::Matrix3d F0 = affine_gradient();
  const Eigen::Matrix3d A = F0 - Eigen::Matrix3d::Identity();
  std::vector<int> nodes;
  for (Side s : sides) {
    const std::vector<int> n = nodes_of(dofs, side_control_points(vol, s));
    nodes.insert(nodes.end(), n.begin(), n.end());
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  DirichletConditions bcs;
  bcs.prescribe("affine boundary", nodes,
                [A](const Eigen::Vector3d& X, double t) -> Eigen::Vector3d { return t * (A * X); });
  ProblemOptions opts;
  opts.formulation = formulation;
  Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::constant({0, 0, 1})), bcs,
                  {}, opts);
  EXPECT_GT(problem.size(), 0);
  Eigen::VectorXd u;
  std::string msg;
  std::vector<solver::NewtonResult> results;
  EXPECT_TRUE(testing::solve_steps(problem, u, 1, testing::tight_newton(1e-12), &msg, &results))
      << msg;
  PatchErrors err;
  for (const auto& r : results) {
    err.iterations += r.iterations;
  }
  materials::PointInput in;
  in.F = F0;
  materials::PointResult exact;
  law->evaluate(in, exact, false);
  double min_J = std::numeric_limits<double>::infinity();
  double max_J = -std::numeric_limits<double>::infinity();
  for (int e = 0; e < space.num_elements(); ++e) {
    for (const PointState& st : problem.element_states(e)) {
      err.F = std::max(err.F, (st.field.F - F0).cwiseAbs().maxCoeff());
      err.S = std::max(err.S, (st.S - exact.S).norm() / exact.S.norm());
      min_J = std::min(min_J, st.J);
      max_J = std::max(max_J, st.J);
    }
  }
  // The committed state's smallest and largest J (kept during assembly, per thread) are those of
  // its element states (det F0 where the patch is exact).
  const continuum::JacobianRange& jr = problem.committed_jacobian_range();
  EXPECT_TRUE(jr.found());
  EXPECT_DOUBLE_EQ(jr.smallest.value, min_J);
  EXPECT_DOUBLE_EQ(jr.largest.value, max_J);
  err.min_J = std::abs(jr.smallest.value - F0.determinant());
  err.max_J = std::abs(jr.largest.value - F0.determinant());
  return err;
}

const std::vector<Side> kAllSides = {Side::u0, Side::u1, Side::v0, Side::v1, Side::w0, Side::w1};
// The shrink cylinder's boundary: the lateral surface w0 and the ends v0, v1 (u0/u1 is the
// interior seam, w1 the interior axis).
const std::vector<Side> kCylinderSides = {Side::w0, Side::v0, Side::v1};

void bspline_patch(int p) {
  // Two elements per direction for p <= 2, one for p = 3, 4 (already 8 and 27 interior control
  // points).
  const geometry::NurbsVolume vol =
      testing::distorted_rational_block(p, p <= 2 ? 2 : 1, 0.15, 11 + p, /*rational=*/false);
  const int exact_points = std::max(p + 1, (3 * p + 1) / 2);
  for (Formulation f : {Formulation::displacement, Formulation::mixed}) {
    const PatchErrors e = run_patch(vol, kAllSides, f, exact_points);
    std::printf(
        "distorted B-spline block p=%d %-12s %d points: |F-F0| %.2e  |S-S0|/|S0| %.2e "
        "(%d Newton iterations)\n",
        p, to_string(f), exact_points, e.F, e.S, e.iterations);
    EXPECT_LT(e.F, 1e-10) << "p = " << p << " " << to_string(f);
    EXPECT_LT(e.min_J, 1e-10) << "p = " << p << " " << to_string(f);
    EXPECT_LT(e.max_J, 1e-10) << "p = " << p << " " << to_string(f);
    EXPECT_LT(e.S, 1e-10) << "p = " << p << " " << to_string(f);
  }
}

TEST(PatchTest, DistortedBSplineBlockIsExactWithExactQuadrature) {
  bspline_patch(1);
  bspline_patch(2);
}

// p = 3, 4 separately: their elements are heavy under the sanitizer build.
TEST(SlowPatchTest, DistortedBSplineBlockOfDegree3And4IsExactWithExactQuadrature) {
  bspline_patch(3);
  bspline_patch(4);
}

// The shrink cylinder with its seam and collapsed axis, built from a polynomial surface: cof(J) is
// polynomial even where det J -> 0 on the axis, so the exact rule reproduces F0 there too.
void polynomial_cylinder_patch(int p) {
  const geometry::NurbsVolume cyl =
      testing::polynomial_shrink_cylinder(0.5, 1.0, p, {0, p == 1 ? 1 : 0, 1});
  for (double w : cyl.weights()) {
    ASSERT_NEAR(w, 1.0, 1e-14);  // degree elevation in homogeneous form leaves round-off
  }
  const int pc = std::max({cyl.degree(0), cyl.degree(1), cyl.degree(2)});
  const int exact_points = std::max(pc + 1, (3 * pc + 1) / 2);
  for (Formulation f : {Formulation::displacement, Formulation::mixed}) {
    const PatchErrors e = run_patch(cyl, kCylinderSides, f, exact_points);
    std::printf(
        "polynomial shrink cylinder (%d,%d,%d) %-12s %d points: |F-F0| %.2e  |S-S0|/|S0| %.2e "
        "(%d Newton iterations)\n",
        cyl.degree(0), cyl.degree(1), cyl.degree(2), to_string(f), exact_points, e.F, e.S,
        e.iterations);
    EXPECT_LT(e.F, 1e-10) << "p = " << p << " " << to_string(f);
    EXPECT_LT(e.min_J, 1e-10) << "p = " << p << " " << to_string(f);
    EXPECT_LT(e.max_J, 1e-10) << "p = " << p << " " << to_string(f);
    EXPECT_LT(e.S, 1e-10) << "p = " << p << " " << to_string(f);
  }
}

TEST(PatchTest, PolynomialShrinkCylinderWithItsAxisIsExactWithExactQuadrature) {
  polynomial_cylinder_patch(1);
  polynomial_cylinder_patch(2);
}

TEST(SlowPatchTest, PolynomialShrinkCylinderOfDegree3And4IsExact) {
  polynomial_cylinder_patch(3);
  polynomial_cylinder_patch(4);
}

// Rational maps: the defect is the quadrature error of the rational integrand: asserted to fall by
// at least 1e2 from p + 1 to p + 4 points per direction (measured: 1e3 to 1e5).
TEST(SlowPatchTest, RationalBlockAndShrinkCylinderDefectIsQuadratureError) {
  for (int p = 1; p <= 4; ++p) {
    const geometry::NurbsVolume block =
        testing::distorted_rational_block(p, p == 1 ? 2 : 1, 0.15, 21 + p);
    const geometry::NurbsVolume cyl = testing::shrink_cylinder(0.5, 1.0, p, {0, 0, 0});
    const int pc = std::max({cyl.degree(0), cyl.degree(1), cyl.degree(2)});
    for (Formulation f : {Formulation::displacement, Formulation::mixed}) {
      const PatchErrors b1 = run_patch(block, kAllSides, f, p + 1);
      const PatchErrors b4 = run_patch(block, kAllSides, f, p + 4);
      const PatchErrors c1 = run_patch(cyl, kCylinderSides, f, pc + 1);
      const PatchErrors c4 = run_patch(cyl, kCylinderSides, f, pc + 4);
      std::printf(
          "p=%d %-12s rational block |F-F0| %.2e (p+1 points) %.2e (p+4), |S-S0|/|S0| "
          "%.2e %.2e | shrink cylinder (%d,%d,%d) |F-F0| %.2e %.2e, |S-S0|/|S0| %.2e "
          "%.2e\n",
          p, to_string(f), b1.F, b4.F, b1.S, b4.S, cyl.degree(0), cyl.degree(1), cyl.degree(2),
          c1.F, c4.F, c1.S, c4.S);
      std::fflush(stdout);
      EXPECT_GT(b1.F, 1e-8) << "a rational block with p + 1 points should show the defect";
      EXPECT_LT(b4.F, 1e-2 * b1.F) << "p = " << p << " " << to_string(f);
      // (The cylinder with degrees (2,2,1) and one radial element has only the axis nodes inside
      // and is exact already: then both are at round-off.)
      EXPECT_LT(c4.F, std::max(1e-2 * c1.F, 1e-13)) << "p = " << p << " " << to_string(f);
      EXPECT_LT(b4.S, 1e-2 * b1.S) << "p = " << p << " " << to_string(f);
      EXPECT_LT(c4.S, std::max(1e-2 * c1.S, 1e-13)) << "p = " << p << " " << to_string(f);
    }
  }
}

}  // namespace
}  // namespace isomuscle::iga
