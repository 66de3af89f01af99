// Stress between quadrature points (iga/quadrature_point_interpolation.hpp, Problem::state_at): the
// interpolation weights are exact for the polynomials they should be, the state at a quadrature
// point is the converged one, and for a rate-dependent Hill muscle the stress at a point between
// quadrature points does not depend on the size of the step that led there (evaluating the law at
// F(xi) with a neighbouring point's history did: a spurious contraction velocity ~ dF / dt). The
// muscle runs (8 s in Release, 4 min under the sanitizers) carry the label slow.
#include <gtest/gtest.h>

#include <cmath>

#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "iga/quadrature_point_interpolation.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"
#include "solver/newton.hpp"

namespace isomuscle::iga {
namespace {

TEST(QuadraturePointWeights, SumToOneHitThePointsAndReproduceTheirPolynomials) {
  // Degrees (2, 3, 1): 3 x 4 x 2 Gauss points; a graded knot vector so elements differ in size.
  geometry::NurbsVolume vol = testing::box(Eigen::Vector3d(2, 1, 1), {2, 3, 1}, {3, 2, 2});
  const Space space(vol);
  ASSERT_EQ(space.points_per_direction(), (std::array<int, 3>{3, 4, 2}));
  const int e = space.num_elements() - 2;
  const Element& el = space.element(e);
  // A polynomial of degree (2, 3, 1) in the element's coordinates is reproduced exactly.
  auto f = [](const Eigen::Vector3d& x) {
    return 1.0 + x[0] - 2.0 * x[0] * x[0] + 0.5 * x[1] * x[1] * x[1] * (1.0 + x[2]) - x[1] * x[2];
  };
  std::vector<double> at_points;
  for (int q = 0; q < space.points_per_element(); ++q)
    at_points.push_back(f(space.parametric(e, q)));
  for (const Eigen::Vector3d& s : {Eigen::Vector3d(0.1, 0.7, 0.3), Eigen::Vector3d(0.0, 1.0, 1.0),
                                   Eigen::Vector3d(0.5, 0.5, 0.5)}) {
    Eigen::Vector3d xi;
    for (int d = 0; d < 3; ++d)
      xi[d] = el.box[d][0] + s[d] * (el.box[d][1] - el.box[d][0]);
    const std::vector<double> w = quadrature_point_weights(space, e, xi);
    double sum = 0.0, value = 0.0;
    for (std::size_t q = 0; q < w.size(); ++q) {
      sum += w[q];
      value += w[q] * at_points[q];
    }
    EXPECT_NEAR(sum, 1.0, 1e-13);
    EXPECT_NEAR(value, f(xi), 1e-12 * std::abs(f(xi)) + 1e-13);
  }
  const std::vector<double> w = quadrature_point_weights(space, e, space.parametric(e, 5));
  for (std::size_t q = 0; q < w.size(); ++q)
    EXPECT_NEAR(w[q], q == 5 ? 1.0 : 0.0, 1e-13);
  EXPECT_THROW(quadrature_point_weights(space, 0, space.parametric(e, 0)), std::invalid_argument);
}

// Newton on one step (t, dt), committed.
void solve_step(Problem& problem, Eigen::VectorXd& u, double t, double dt) {
  solver::NewtonSolver newton(testing::tight_newton(1e-10));
  problem.begin_step(t, dt);
  ASSERT_TRUE(problem.predict(u).ok);
  const solver::NewtonResult r = newton.solve(problem, u);
  ASSERT_TRUE(r.converged) << "t = " << t << ": " << r.message;
  problem.commit_step(u);
}

double fibre_stress(const PointState& st) {
  return st.fibre_deformed.dot(st.cauchy * st.fibre_deformed);
}

TEST(SlowStateInterpolation, ActiveMuscleStressBetweenPointsDoesNotDependOnTheStepSize) {
  // The barrel with both ends clamped, isometric contraction of the Hill muscles (fibres along the
  // isocurves v; tang2009 active from t = 0, full after 5 ms; lu2010 ramping), mixed formulation:
  // F varies inside the elements because the cross-section does. After 0.1 s in 10 ms steps one
  // more step of 1e-7 s hardly changes the state, so the stress between the points must not
  // change either. (The law at F(xi) with the nearest point's history gave +13 % (tang2009) and
  // +8 % (lu2010) after the short step, and 37 % / 26 % above the interpolated stress before it.)
  const geometry::NurbsVolume vol = testing::shrink_barrel(2, {1, 1, 1});
  const Space space(vol);
  const DofMap dofs(vol);
  DirichletConditions bcs;
  bcs.fix("end v0", nodes_of(dofs, side_control_points(vol, Side::v0)));
  bcs.fix("end v1", nodes_of(dofs, side_control_points(vol, Side::v1)));
  for (const char* model : {"tang2009", "lu2010"}) {
    const auto law = materials::make_material(model);
    ProblemOptions opts;
    opts.formulation = Formulation::mixed;
    Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::isocurve(1)), bcs, {},
                    opts);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
    for (int k = 1; k <= 10; ++k) {
      solve_step(problem, u, 1e-2 * k, 1e-2);
      if (::testing::Test::HasFatalFailure())
        return;
    }
    const Eigen::Vector3d xi(0.11, 0.23, 0.4);  // between the points of its element, off the axis
    const int e = space.locate(xi);
    const PointState before = problem.state_at(xi);
    const std::vector<PointState> states = problem.element_states(e);
    // The state at a quadrature point is the converged one.
    const PointState at_q = problem.state_at(space.parametric(e, 4));
    EXPECT_LT((at_q.cauchy - states[4].cauchy).norm(), 1e-10 * states[4].cauchy.norm()) << model;
    // F varies inside the element: the fibre stretch differs between xi and the element's points.
    double variation = 0.0;
    for (const PointState& s : states)
      variation = std::max(variation, std::abs(s.fibre_stretch - before.fibre_stretch));
    EXPECT_GT(variation, 1e-4) << model;

    solve_step(problem, u, 0.1 + 1e-7, 1e-7);
    if (::testing::Test::HasFatalFailure())
      return;
    const PointState after = problem.state_at(xi);
    const double s0 = fibre_stress(before), s1 = fibre_stress(after);
    std::printf(
        "%s: fibre stress at xi %.6e Pa, after a 1e-7 s step %.6e Pa (stretch variation "
        "in the element %.1e)\n",
        model, s0, s1, variation);
    EXPECT_GT(s0, 5e4) << model << ": an isometric muscle pulls (sigma0 = 2.2e5, 7e5 Pa)";
    EXPECT_LT(std::abs(s1 - s0), 1e-3 * s0) << model;
    EXPECT_LT((after.cauchy - before.cauchy).norm(), 1e-3 * before.cauchy.norm()) << model;
  }
}

}  // namespace
}  // namespace isomuscle::iga
