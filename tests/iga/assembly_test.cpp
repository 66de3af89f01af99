// Assembly: 1 and 2 threads give the same residual and tangent (element colouring, fixed order),
// evaluation failures name the place and never produce NaN, and the Problem's outputs (volume,
// reactions, point values, tessellation) are consistent.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/loads.hpp"
#include "iga/problem.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::iga {
namespace {

TEST(Assembly, OneAndTwoThreadsGiveTheSameResidualAndTangent) {
  const geometry::NurbsVolume vol = testing::shrink_barrel(2, {1, 1, 1});
  const Space space(vol);
  const DofMap dofs(vol);
  const auto law = materials::make_material("lu2010");
  DirichletConditions bcs;
  bcs.fix("end v0", nodes_of(dofs, side_control_points(vol, Side::v0)));
  for (Formulation f : {Formulation::displacement, Formulation::mixed}) {
    ProblemOptions opts;
    opts.formulation = f;
    Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::isocurve(1)), bcs, {},
                    opts);
    EXPECT_GT(problem.num_colours(), 1);
    Eigen::VectorXd u(problem.size());
    for (int i = 0; i < u.size(); ++i) {
      u[i] = 1e-5 * std::sin(0.37 * i);  // m
    }
    Eigen::VectorXd r1, r2;
    solver::SparseMatrix K1, K2;
    // begin_step before each: the mixed formulation's first evaluation of a step projects exactly
    // (a second evaluation would update p~, J~ from the first one's base, element_kernels.hpp).
    problem.set_threads(1);
    problem.begin_step(0.05, 0.01);
    ASSERT_TRUE(problem.evaluate(u, r1, &K1).ok);
    problem.set_threads(2);
    problem.begin_step(0.05, 0.01);
    ASSERT_TRUE(problem.evaluate(u, r2, &K2).ok);
    const double dr = (r1 - r2).norm() / r1.norm();
    const double dk = (Eigen::Map<const Eigen::VectorXd>(K1.valuePtr(), K1.nonZeros()) -
                       Eigen::Map<const Eigen::VectorXd>(K2.valuePtr(), K2.nonZeros()))
                          .norm() /
                      Eigen::Map<const Eigen::VectorXd>(K1.valuePtr(), K1.nonZeros()).norm();
    std::printf("%s: 1 vs 2 threads, relative difference residual %.1e, tangent %.1e\n",
                to_string(f), dr, dk);
    EXPECT_LE(dr, 1e-12);
    EXPECT_LE(dk, 1e-12);
  }
}

TEST(Assembly, InvertedElementIsAFailureNamingThePlace) {
  const geometry::NurbsVolume vol = testing::box(Eigen::Vector3d(1, 1, 1), {2, 2, 2}, {2, 2, 2});
  const Space space(vol);
  const DofMap dofs(vol);
  const auto law = materials::make_material("neo_hookean");
  DirichletConditions bcs;
  bcs.fix("u0", nodes_of(dofs, side_control_points(vol, Side::u0)));
  Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::constant({0, 0, 1})), bcs);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  // Push one interior control point through its neighbours: x -> x - 2.
  const int node = dofs.node(vol.index(2, 2, 2));
  u[problem.constraints().free_index(DofMap::dof(node, 0))] = -2.0;
  Eigen::VectorXd r;
  solver::SparseMatrix K;
  const solver::EvaluationStatus st = problem.evaluate(u, r, &K);
  EXPECT_FALSE(st.ok);
  EXPECT_NE(st.message.find("element "), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("quadrature point"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("<= 0 (inverted)"), std::string::npos) << st.message;
}

TEST(Assembly, ReactionsBalanceLoadsAndOutputsAreConsistent) {
  // Cantilever block 2 x 1 x 1, clamped at x = 0, traction 10 Pa along z on x = 2.
  const geometry::NurbsVolume vol = testing::box(Eigen::Vector3d(2, 1, 1), {2, 2, 2}, {2, 1, 1});
  const Space space(vol);
  const DofMap dofs(vol);
  EXPECT_NEAR(side_area(space, Side::u1), 1.0, 1e-14);
  const auto law = materials::make_material("neo_hookean", {{"C10", 1000.0}, {"K", 1e4}});
  DirichletConditions bcs;
  const std::vector<int> clamped = nodes_of(dofs, side_control_points(vol, Side::u0));
  bcs.fix("clamped", clamped);
  Loads loads;
  loads.surface.push_back(
      {"tip", Side::u1, [](const Eigen::Vector3d&, double t) -> Eigen::Vector3d {
         return Eigen::Vector3d(0, 0, 10.0 * t);
       }});
  Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::constant({1, 0, 0})), bcs,
                  loads);
  Eigen::VectorXd u;
  std::string msg;
  ASSERT_TRUE(testing::solve_steps(problem, u, 2, testing::tight_newton(1e-11), &msg)) << msg;
  Eigen::VectorXd f_int;
  ASSERT_TRUE(problem.internal_force(u, f_int).ok);
  const Eigen::Vector3d reaction = problem.sum_over_nodes(f_int, clamped);
  // The internal forces sum to zero, so at the support they are minus the applied load: the
  // support reaction on the body is (0, 0, -10) N.
  EXPECT_NEAR(reaction.z(), -10.0, 1e-8);
  EXPECT_NEAR(reaction.x(), 0.0, 1e-8);
  const Eigen::VectorXd& full = problem.committed_displacement();
  EXPECT_GT(problem.displacement_at(full, Eigen::Vector3d(1, 0.5, 0.5)).z(), 0.0);
  EXPECT_EQ(problem.displacement_at(full, Eigen::Vector3d(0, 0.3, 0.7)).norm(), 0.0);
  const double V = problem.current_volume(full);
  EXPECT_NEAR(V, 2.0, 0.01);
  const PointState st = problem.state_at(Eigen::Vector3d(0.25, 0.5, 0.5));
  EXPECT_TRUE(st.cauchy.allFinite());
  EXPECT_NEAR(st.cauchy(0, 2), st.cauchy(2, 0), 1e-9 * st.cauchy.norm());
  EXPECT_GT(st.J, 0.0);
  // Element states reproduce state_at_point.
  const std::vector<PointState> states = problem.element_states(1);
  const PointState one = problem.state_at_point(1, 5);
  EXPECT_LT((states[5].S - one.S).norm(), 1e-10 * one.S.norm());
  const Tessellation t = problem.tessellate(full, 2);
  EXPECT_EQ(t.grid, (std::array<int, 3>{5, 3, 3}));
  EXPECT_EQ(t.hexahedra.size(), 16u);
  for (std::size_t i = 0; i < t.reference.size(); ++i) {
    EXPECT_LT((t.reference[i] - vol.evaluate(t.parametric[i])).norm(), 1e-13);
  }
}

TEST(BoundaryConditions, SelectorsConflictsAndErrors) {
  const geometry::NurbsVolume vol = testing::box(Eigen::Vector3d(1, 1, 1), {2, 2, 2}, {2, 2, 2});
  const DofMap dofs(vol);
  EXPECT_EQ(side_control_points(vol, Side::w1).size(), 16u);
  EXPECT_EQ(plane_control_points(vol, Eigen::Vector3d(0.25, 0, 0), Eigen::Vector3d(2, 0, 0), 1e-12)
                .size(),
            16u);  // x = 0.25: the second control layer (Greville abscissa 0.25)
  EXPECT_EQ(parse_side("v1"), Side::v1);
  EXPECT_THROW(parse_side("top"), std::invalid_argument);
  DirichletConditions bcs;
  EXPECT_THROW(bcs.symmetry("oblique", {0}, Eigen::Vector3d(1, 1, 0)), std::invalid_argument);
  bcs.symmetry("x = 0", nodes_of(dofs, side_control_points(vol, Side::u0)), {-1, 0, 0});
  bcs.fix("u0 again", nodes_of(dofs, side_control_points(vol, Side::u0)));  // zero twice: fine
  bcs.move_with_velocity("pulled", nodes_of(dofs, side_control_points(vol, Side::u1)),
                         Eigen::Vector3d(0.1, 0, 0));
  const ConstrainedDofs c(dofs, bcs);
  EXPECT_EQ(c.num_free(), dofs.num_dofs() - 2 * 16 * 3);
  Eigen::VectorXd full = Eigen::VectorXd::Zero(dofs.num_dofs());
  c.apply_prescribed(2.0, full);
  const int n1 = dofs.node(vol.index(vol.count(0) - 1, 1, 1));
  EXPECT_DOUBLE_EQ(full[DofMap::dof(n1, 0)], 0.2);
  DirichletConditions conflict = bcs;
  conflict.move_with_velocity("pulled twice", {n1}, Eigen::Vector3d(0, 0.1, 0));
  try {
    const ConstrainedDofs bad(dofs, conflict);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("both prescribe"), std::string::npos) << e.what();
  }
  DirichletConditions outside;
  outside.fix_point("bad node", dofs.num_nodes(), {true, false, false});
  EXPECT_THROW(ConstrainedDofs(dofs, outside), std::invalid_argument);
}

TEST(FibreDirections, ModesAndErrors) {
  const geometry::NurbsVolume vol = testing::shrink_cylinder(0.5, 2.0, 2, {0, 0, 0});
  const Space space(vol);
  // Along the centreline (v): the isocurve tangent is the axis everywhere.
  for (const Eigen::Vector3d& n : fibre_directions(space, FibreSpec::isocurve(1))) {
    EXPECT_NEAR(std::abs(n.z()), 1.0, 1e-12);
  }
  // Around (u): in the cross-section plane (z depends on v only). (Inside the shrink solid the
  // u-isocurves are not concentric circles: the construction blends homogeneous coordinates
  // linearly towards the centreline.)
  for (const Eigen::Vector3d& n : fibre_directions(space, FibreSpec::isocurve(0))) {
    EXPECT_LT(std::abs(n.z()), 1e-12);
  }
  // Two segments meeting at (0, 0, 1): points below z = 1 take the first, above the second.
  const FibreSpec two = FibreSpec::segments(
      {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0.2, 1), Eigen::Vector3d(0, 0, 2)});
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_LT((fibre_direction(two, I, Eigen::Vector3d(0, 0, 0.3)) -
             Eigen::Vector3d(0, 0.2, 1).normalized())
                .norm(),
            1e-14);
  EXPECT_LT((fibre_direction(two, I, Eigen::Vector3d(0, 0, 1.7)) -
             Eigen::Vector3d(0, -0.2, 1).normalized())
                .norm(),
            1e-14);
  // On the convex side of the joint (y > 0.2, beyond the ends of both segments) the distance to
  // either segment is the distance to the joint itself; the bisecting plane z = 1 still decides.
  for (const double y : {0.25, 0.5, 3.0}) {
    EXPECT_LT((fibre_direction(two, I, Eigen::Vector3d(0.1, y, 0.999)) -
               Eigen::Vector3d(0, 0.2, 1).normalized())
                  .norm(),
              1e-14)
        << "y = " << y;
    EXPECT_LT((fibre_direction(two, I, Eigen::Vector3d(0.1, y, 1.001)) -
               Eigen::Vector3d(0, -0.2, 1).normalized())
                  .norm(),
              1e-14)
        << "y = " << y;
  }
  // Three segments: the second joint's plane is crossed only after the first's.
  const FibreSpec three = FibreSpec::segments({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                               Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(0, 1, 0)});
  EXPECT_LT((fibre_direction(three, I, {0.5, -0.2, 0}) - Eigen::Vector3d::UnitX()).norm(), 1e-15);
  EXPECT_LT((fibre_direction(three, I, {1.2, 0.5, 0}) - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  EXPECT_LT((fibre_direction(three, I, {0.5, 1.2, 0}) + Eigen::Vector3d::UnitX()).norm(), 1e-15);
  EXPECT_THROW(FibreSpec::segments({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1),
                                    Eigen::Vector3d(0, 0, 0.5)}),
               std::invalid_argument);
  // Cut at the isoparametric surface w = 0.5 instead: the parameter decides, not the position.
  const FibreSpec cut = FibreSpec::segments_cut_at(
      {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0.2, 1), Eigen::Vector3d(0, 0, 2)}, 2, {0.5});
  EXPECT_LT((fibre_direction(cut, I, {0, 0, 1.7}, {0.3, 0.3, 0.49}) -
             Eigen::Vector3d(0, 0.2, 1).normalized())
                .norm(),
            1e-14);
  EXPECT_LT((fibre_direction(cut, I, {0, 0, 0.3}, {0.3, 0.3, 0.51}) -
             Eigen::Vector3d(0, -0.2, 1).normalized())
                .norm(),
            1e-14);
  EXPECT_THROW(fibre_direction(cut, I, {0, 0, 0.3}), std::invalid_argument);  // xi needed
  EXPECT_THROW(FibreSpec::segments_cut_at(cut.polyline, 2, {}), std::invalid_argument);
  EXPECT_THROW(FibreSpec::segments_cut_at(cut.polyline, 3, {0.5}), std::invalid_argument);
  EXPECT_THROW(FibreSpec::segments_cut_at(three.polyline, 1, {0.6, 0.4}), std::invalid_argument);
  EXPECT_LT((fibre_direction(FibreSpec::origin_to_insertion({1, 1, 1}, {1, 1, 3}), I, {0, 0, 0}) -
             Eigen::Vector3d::UnitZ())
                .norm(),
            1e-15);
  EXPECT_THROW(FibreSpec::isocurve(3), std::invalid_argument);
  EXPECT_THROW(FibreSpec::segments({Eigen::Vector3d(0, 0, 0)}), std::invalid_argument);
  EXPECT_THROW(FibreSpec::constant(Eigen::Vector3d::Zero()), std::invalid_argument);
  Eigen::Matrix3d collapsed = I;
  collapsed.col(0).setZero();  // the direction around the axis on the axis itself
  EXPECT_THROW(fibre_direction(FibreSpec::isocurve(0), collapsed, {0, 0, 1}),
               std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::iga
