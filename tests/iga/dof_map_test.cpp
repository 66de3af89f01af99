// DOF merging of coincident control points (closed seam, collapsed centreline rows): without it the
// field tears at the seam and on the axis and the constrained tangent is singular; with it the
// field is continuous and CHOLMOD factorises the tangent.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstdio>

#include "geometry/coincident_points.hpp"
#include "iga/dof_map.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/problem.hpp"
#include "iga_test_support.hpp"
#include "materials/material_factory.hpp"
#include "solver/linear_solver.hpp"

namespace isomuscle::iga {
namespace {

TEST(DofMap, MergesSeamAndAxisOfShrinkCylinder) {
  const geometry::NurbsVolume v = testing::shrink_cylinder(0.5, 1.0, 2, {1, 1, 1});
  const DofMap merged(v);
  const int nu = v.count(0), nv = v.count(1), nw = v.count(2);
  // Distinct points: per v row, (nu - 1) seam-merged points on each of the nw - 1 off-axis rings,
  // plus one axis point.
  EXPECT_EQ(merged.num_nodes(), nv * ((nu - 1) * (nw - 1) + 1));
  for (int k = 0; k < nw; ++k) {
    for (int j = 0; j < nv; ++j) {
      EXPECT_EQ(merged.node(v.index(0, j, k)), merged.node(v.index(nu - 1, j, k)));  // seam
    }
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 1; i < nu; ++i) {
      EXPECT_EQ(merged.node(v.index(0, j, nw - 1)), merged.node(v.index(i, j, nw - 1)));  // axis
    }
  }
  const DofMap plain = DofMap::unmerged(v);
  EXPECT_EQ(plain.num_nodes(), v.num_control_points());
  EXPECT_EQ(plain.num_merged_nodes(), 0);
  EXPECT_EQ(merged.num_merged_nodes(), nv * nw);  // a seam pair per ring, one axis point per row
}

TEST(DofMap, RejectsGroupingOfDistinctPoints) {
  const geometry::NurbsVolume v = testing::box(Eigen::Vector3d(1, 1, 1), {1, 1, 1}, {1, 1, 1});
  std::vector<int> node_of = {0, 0, 1, 2, 3, 4, 5, 6};  // control points 0 and 1 are 1 m apart
  try {
    const DofMap d(v, node_of);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not the same physical point"), std::string::npos);
  }
  EXPECT_THROW(DofMap(v, std::vector<int>{0, 1, 2, 3, 4, 5, 6, 8}), std::invalid_argument);
  EXPECT_THROW(DofMap(v, 0.5), std::invalid_argument);
}

// Twisting the end v1 of a cylinder fixed at v0 (a loading that is smooth in the merged space):
// with one DOF set per control point the seam copies and the axis copies are independent unknowns.
struct TwistRun {
  bool factorised = false;
  double min_eigenvalue = 0.0;  // smallest eigenvalue of the constrained tangent at u = 0
  double seam_jump = 0.0;       // max |u(0, v, w) - u(1, v, w)| over control rows after one solve
  double axis_spread = 0.0;     // max spread of the displacements of the axis copies
};

TwistRun twist(const geometry::NurbsVolume& v, const DofMap& dofs) {
  const Space space(v);
  const auto law = materials::make_material("neo_hookean", {{"C10", 1.0}, {"K", 50.0}});
  DirichletConditions bcs;
  bcs.fix("fixed end v0", nodes_of(dofs, side_control_points(v, Side::v0)));
  const double angle = 0.3;
  bcs.prescribe("twisted end v1", nodes_of(dofs, side_control_points(v, Side::v1)),
                [angle](const Eigen::Vector3d& X, double t) -> Eigen::Vector3d {
                  const double a = angle * t;
                  return Eigen::Vector3d(std::cos(a) * X.x() - std::sin(a) * X.y() - X.x(),
                                         std::sin(a) * X.x() + std::cos(a) * X.y() - X.y(), 0.0);
                });
  ProblemOptions opts;
  opts.formulation = Formulation::displacement;
  Problem problem(space, dofs, *law, fibre_directions(space, FibreSpec::constant({0, 0, 1})), bcs,
                  {}, opts);
  TwistRun run;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(problem.size());
  Eigen::VectorXd r;
  solver::SparseMatrix K;
  problem.begin_step(1.0, 1.0);
  EXPECT_TRUE(problem.evaluate(u, r, &K).ok);
  const solver::SparseMatrix full = K.selfadjointView<Eigen::Upper>();
  const Eigen::MatrixXd dense = Eigen::MatrixXd(full);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense, Eigen::EigenvaluesOnly);
  run.min_eigenvalue = eig.eigenvalues().minCoeff() / eig.eigenvalues().maxCoeff();
  solver::LinearSolverSettings ls;
  ls.indefinite = solver::IndefiniteResponse::Fail;
  solver::LinearSolver linear(ls);
  run.factorised = linear.factorize(K).ok;
  if (run.factorised) {
    Eigen::VectorXd du;
    linear.solve(-r, du);
    const Eigen::VectorXd full = problem.full_displacement(u + du);
    const int nu = v.count(0), nv = v.count(1), nw = v.count(2);
    for (int k = 0; k < nw; ++k) {
      for (int j = 0; j < nv; ++j) {
        const Eigen::Vector3d a = full.segment<3>(3 * dofs.node(v.index(0, j, k)));
        const Eigen::Vector3d b = full.segment<3>(3 * dofs.node(v.index(nu - 1, j, k)));
        run.seam_jump = std::max(run.seam_jump, (a - b).norm());
      }
    }
    for (int j = 0; j < nv; ++j) {
      const Eigen::Vector3d a = full.segment<3>(3 * dofs.node(v.index(0, j, nw - 1)));
      for (int i = 1; i < nu; ++i) {
        const Eigen::Vector3d b = full.segment<3>(3 * dofs.node(v.index(i, j, nw - 1)));
        run.axis_spread = std::max(run.axis_spread, (a - b).norm());
      }
    }
  }
  return run;
}

TEST(DofMap, WithoutMergeTheFieldTearsWithMergeTheTangentHasFullRank) {
  const geometry::NurbsVolume v = testing::shrink_cylinder(0.5, 1.0, 2, {1, 1, 0});
  const TwistRun merged = twist(v, DofMap(v));
  const TwistRun plain = twist(v, DofMap::unmerged(v));
  std::printf(
      "merged:   CHOLMOD %s, lambda_min/lambda_max %.3e, seam jump %.2e m, axis spread "
      "%.2e m\n",
      merged.factorised ? "ok" : "failed", merged.min_eigenvalue, merged.seam_jump,
      merged.axis_spread);
  std::printf(
      "unmerged: CHOLMOD %s, lambda_min/lambda_max %.3e, seam jump %.2e m, axis spread "
      "%.2e m\n",
      plain.factorised ? "ok" : "failed", plain.min_eigenvalue, plain.seam_jump, plain.axis_spread);
  EXPECT_TRUE(merged.factorised);
  EXPECT_GT(merged.min_eigenvalue, 1e-8);
  EXPECT_EQ(merged.seam_jump, 0.0);
  EXPECT_EQ(merged.axis_spread, 0.0);
  // Unmerged: the copies on the axis, where every function of the collapsed row has the same
  // trace, are free to move apart; the field tears.
  if (plain.factorised) {
    EXPECT_GT(std::max(plain.seam_jump, plain.axis_spread), 1e-6);
  } else {
    EXPECT_LT(plain.min_eigenvalue, 1e-12);
  }
}

}  // namespace
}  // namespace isomuscle::iga
