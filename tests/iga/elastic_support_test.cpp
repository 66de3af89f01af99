// Elastic (Winkler) supports (iga/elastic_support.hpp) on an affine box, where the exact discrete
// solution is known:
// * the spring matrix of a side sums, per held component, to k times the side's area (the NURBS
//   basis is a partition of unity), is symmetric and holds nothing in the free components;
// * a box pulled by a dead traction t on its top, held on its bottom by springs along z only (and
//   by the symmetry planes x = 0 and y = 0) stretches homogeneously, which the space reproduces, so
//   the whole bottom rises by t / k exactly, and the top moves by t / k more than the same box on a
//   bottom fixed along z; the internal force at the bottom is the springs' force on the body,
//   -t A. In both formulations, at a stretch of 14 % (nonlinear neo-Hookean);
// * the residual's tangent with springs matches central differences.
#include <gtest/gtest.h>

#include <random>

#include "iga/dof_map.hpp"
#include "iga/elastic_support.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/loads.hpp"
#include "iga/problem.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"

namespace isomuscle::iga {
namespace {

constexpr double kTraction = 300.0;   // Pa on the top, at t = 1
constexpr double kStiffness = 2.0e4;  // Pa/m: the bottom rises 15 mm

TEST(ElasticSupport, SideMatrixSumsToStiffnessTimesAreaOnTheHeldComponents) {
  const geometry::NurbsVolume vol =
      testing::box(Eigen::Vector3d(0.2, 0.1, 0.3), {2, 3, 2}, {2, 3, 2});
  const Space space(vol);
  const std::vector<SupportElementMatrix> m =
      support_element_matrices(space, {{"bottom", Side::w0, kStiffness, {true, false, true}}});
  ASSERT_EQ(m.size(), 6u);  // the 2 x 3 elements of the bottom layer
  Eigen::Vector3d sums = Eigen::Vector3d::Zero();
  for (const SupportElementMatrix& s : m) {
    EXPECT_EQ(s.matrix.rows(), 3 * space.functions_per_element());
    EXPECT_LT((s.matrix - s.matrix.transpose()).norm(), 1e-12 * s.matrix.norm());
    for (Eigen::Index i = 0; i < s.matrix.rows(); ++i)
      for (Eigen::Index j = 0; j < s.matrix.cols(); ++j) {
        if (s.matrix(i, j) != 0.0) {
          EXPECT_EQ(i % 3, j % 3);  // no coupling between components
          sums[i % 3] += s.matrix(i, j);
        }
      }
  }
  EXPECT_NEAR(sums.x(), kStiffness * 0.2 * 0.1, 1e-12 * kStiffness);
  EXPECT_EQ(sums.y(), 0.0);
  EXPECT_NEAR(sums.z(), kStiffness * 0.2 * 0.1, 1e-12 * kStiffness);
  // Two supports on one side add up in one matrix per element.
  const std::vector<SupportElementMatrix> twice =
      support_element_matrices(space, {{"a", Side::w0, kStiffness, {true, false, true}},
                                       {"b", Side::w0, kStiffness, {true, false, true}}});
  ASSERT_EQ(twice.size(), m.size());
  EXPECT_LT((twice[0].matrix - 2.0 * m[0].matrix).norm(), 1e-12 * m[0].matrix.norm());
}

TEST(ElasticSupport, BadSupportsAreRefusedByName) {
  const geometry::NurbsVolume vol = testing::box(Eigen::Vector3d(1, 1, 1), {2, 2, 2}, {1, 1, 1});
  const Space space(vol);
  const auto message = [&](const ElasticSupport& s) {
    try {
      support_element_matrices(space, {s});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no throw");
  };
  EXPECT_EQ(message({"jaw", Side::u0, 0.0, {true, true, true}}),
            "elastic support 'jaw': the stiffness must be finite and > 0 (Pa/m)");
  EXPECT_EQ(message({"jaw", Side::u0, 1.0, {false, false, false}}),
            "elastic support 'jaw' holds no component");
}

// The 0.2 x 0.1 x 0.3 m box of degree 2, 2 x 1 x 2 elements, and its face x = 0 held along x.
geometry::NurbsVolume springs_box() {
  return testing::box(Eigen::Vector3d(0.2, 0.1, 0.3), {2, 2, 2}, {2, 1, 2});
}

DirichletConditions held_at_x0(const geometry::NurbsVolume& vol, const DofMap& dofs) {
  DirichletConditions bcs;
  bcs.fix("x = 0", nodes_of(dofs, side_control_points(vol, Side::u0)), {true, false, false});
  return bcs;
}

struct Pulled {
  Eigen::Vector3d top = Eigen::Vector3d::Zero();  // displacement of the top's corner, m
  double bottom_min = 0.0, bottom_max = 0.0;      // u_z over the bottom's control points, m
  Eigen::Vector3d bottom_force = Eigen::Vector3d::Zero();  // internal force summed there, N
};

// The box pulled along z by kTraction on w1, with x = 0 and y = 0 held by
// symmetry, the bottom w0 on springs along z (elastic) or fixed along z.
Pulled pull(Formulation formulation, bool elastic) {
  const geometry::NurbsVolume vol = springs_box();
  const Space space(vol);
  const DofMap dofs(vol);
  const auto law = materials::make_material("neo_hookean", {{"C10", 500.0}, {"K", 1.0e5}});
  DirichletConditions bcs = held_at_x0(vol, dofs);
  bcs.fix("y = 0", nodes_of(dofs, side_control_points(vol, Side::v0)), {false, true, false});
  const std::vector<int> bottom = nodes_of(dofs, side_control_points(vol, Side::w0));
  if (!elastic)
    bcs.fix("bottom", bottom, {false, false, true});
  Loads loads;
  loads.surface.push_back({"top", Side::w1, [](const Eigen::Vector3d&, double t) {
                             return Eigen::Vector3d(0.0, 0.0, kTraction * t);
                           }});
  ProblemOptions opts;
  opts.formulation = formulation;
  Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::constant({0, 0, 1})), bcs,
                  loads, opts);
  if (elastic)
    problem.set_elastic_supports({{"bottom", Side::w0, kStiffness, {false, false, true}}});
  Eigen::VectorXd u;
  std::string msg;
  EXPECT_TRUE(testing::solve_steps(problem, u, 4, testing::tight_newton(1e-12), &msg)) << msg;
  Pulled out;
  const Eigen::VectorXd& full = problem.committed_displacement();
  out.top = problem.displacement_at(full, Eigen::Vector3d(1, 1, 1));
  out.bottom_min = 1e300;
  out.bottom_max = -1e300;
  for (int n : bottom) {
    out.bottom_min = std::min(out.bottom_min, full[3 * n + 2]);
    out.bottom_max = std::max(out.bottom_max, full[3 * n + 2]);
  }
  Eigen::VectorXd f_int;
  EXPECT_TRUE(problem.internal_force(u, f_int).ok);
  out.bottom_force = problem.sum_over_nodes(f_int, bottom);
  return out;
}

TEST(ElasticSupport, PulledBoxRisesOnItsSpringsByTractionOverStiffness) {
  const double rise = kTraction / kStiffness;  // 15 mm
  const double area = 0.2 * 0.1;
  for (const Formulation f : {Formulation::displacement, Formulation::mixed}) {
    SCOPED_TRACE(to_string(f));
    const Pulled sprung = pull(f, true);
    const Pulled held = pull(f, false);
    EXPECT_NEAR(sprung.bottom_min, rise, 1e-9 * rise);
    EXPECT_NEAR(sprung.bottom_max, rise, 1e-9 * rise);
    EXPECT_EQ(held.bottom_max, 0.0);
    // The stretch is the same, the springs add a rigid rise.
    EXPECT_GT(held.top.z(), 0.1 * 0.3);  // a nonlinear stretch: over 10 %
    EXPECT_NEAR(sprung.top.z() - held.top.z(), rise, 1e-9 * rise);
    EXPECT_NEAR(sprung.top.x(), held.top.x(), 1e-9 * std::abs(held.top.x()));
    EXPECT_LT(held.top.x(), 0.0);  // the box narrows
    // The springs' force on the body, as the reaction of a fixed bottom.
    EXPECT_NEAR(sprung.bottom_force.z(), -kTraction * area, 1e-9 * kTraction * area);
    EXPECT_NEAR(held.bottom_force.z(), -kTraction * area, 1e-9 * kTraction * area);
  }
}

TEST(ElasticSupport, TangentWithSpringsMatchesCentralDifferences) {
  const geometry::NurbsVolume vol = springs_box();
  const Space space(vol);
  const DofMap dofs(vol);
  const auto law = materials::make_material("neo_hookean", {{"C10", 500.0}, {"K", 1.0e4}});
  const DirichletConditions bcs = held_at_x0(vol, dofs);
  ProblemOptions opts;
  opts.formulation = Formulation::displacement;
  opts.storage = solver::MatrixStorage::Full;
  Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::constant({0, 0, 1})), bcs,
                  {}, opts);
  problem.set_elastic_supports({{"bottom", Side::w0, kStiffness, {true, true, true}},
                                {"side", Side::u1, 3.0 * kStiffness, {true, false, false}}});
  problem.begin_step(1.0, 1.0);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd u(problem.size());
  for (int i = 0; i < u.size(); ++i)
    u[i] = 3e-3 * unit(gen);
  Eigen::VectorXd r0;
  solver::SparseMatrix K;
  ASSERT_TRUE(problem.evaluate(u, r0, &K).ok);
  const double h = 1e-7;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd dir(problem.size());
    for (int i = 0; i < dir.size(); ++i)
      dir[i] = unit(gen);
    Eigen::VectorXd rp, rm;
    ASSERT_TRUE(problem.evaluate(u + h * dir, rp, nullptr).ok);
    ASSERT_TRUE(problem.evaluate(u - h * dir, rm, nullptr).ok);
    const Eigen::VectorXd Kv = K * dir;
    EXPECT_LT((Kv - (rp - rm) / (2.0 * h)).norm(), 1e-6 * Kv.norm());
  }
  // The springs are in it: without them the same residual differs by K_s u.
  Problem bare(space, dofs, *law, fibre_directions(space, FibreSpec::constant({0, 0, 1})), bcs, {},
               opts);
  bare.begin_step(1.0, 1.0);
  Eigen::VectorXd r_bare;
  ASSERT_TRUE(bare.evaluate(u, r_bare, nullptr).ok);
  EXPECT_GT((r0 - r_bare).norm(), 1e-3 * r0.norm());
}

}  // namespace
}  // namespace isomuscle::iga
