// solution.h5 (io/solution_file.hpp) read back exactly; the sampler evaluates the stored field at
// parameters and at reference points; bad input is refused before anything is written.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/refinement.hpp"
#include "geometry/shapes.hpp"
#include "geometry/shrink.hpp"
#include "io/solution_file.hpp"
#include "io/solution_sampler.hpp"
#include "io_test_util.hpp"

namespace isomuscle::io {
namespace {

using testing_util::fresh_directory;

// The barrel's shrink solid and a refined copy of it (exact refinement: same parametrisation).
struct Solids {
  geometry::NurbsVolume coarse, fine;
};
Solids barrel_solids() {
  const geometry::NurbsSurface surface = geometry::barrel(0.05, 0.0045, 0.00875);
  Solids s;
  s.coarse = geometry::shrink_to_centreline(surface, 0);
  s.fine = geometry::refine_uniform(geometry::elevate_degree(s.coarse, 2, 1), 1, 2);
  return s;
}

// A smooth field given by its control-point values: u_a = A X_a + b. NURBS reproduce affine
// fields exactly (sum R_a = 1, sum R_a X_a = X), so u(xi) = A X(xi) + b everywhere.
DisplacementRows affine_field(const geometry::NurbsVolume& v, const Eigen::Matrix3d& A,
                              const Eigen::Vector3d& b) {
  DisplacementRows u(v.num_control_points(), 3);
  for (int a = 0; a < v.num_control_points(); ++a)
    u.row(a) = (A * v.points()[a] + b).transpose();
  return u;
}

TEST(SolutionFile, StepsReadBackExactlyAndTheFieldIsEvaluatedAnywhere) {
  const std::filesystem::path dir = fresh_directory("solution");
  const Solids s = barrel_solids();
  Eigen::Matrix3d A;
  A << 0.01, 0.002, 0.0, -0.003, 0.02, 0.001, 0.0, 0.004, -0.05;
  const Eigen::Vector3d b(1e-4, -2e-4, 3e-4);
  const DisplacementRows u1 = affine_field(s.fine, A, b);
  const DisplacementRows u2 = affine_field(s.fine, 2.0 * A, b);
  {
    SolutionWriter writer(dir / "solution.h5", s.coarse, s.fine);
    writer.write_step(0.1, u1);
    writer.write_step(0.2, u2);
    EXPECT_EQ(writer.steps(), 2u);
  }
  const StoredSolution r = read_solution(dir / "solution.h5");
  EXPECT_EQ(r.discretisation, "iga");
  ASSERT_TRUE(r.iga.has_value());
  EXPECT_EQ(r.times, (std::vector<double>{0.1, 0.2}));
  ASSERT_EQ(r.displacement.size(), 2u);
  EXPECT_EQ(r.displacement[0], u1);
  EXPECT_EQ(r.displacement[1], u2);
  EXPECT_EQ(r.geometry.points(), s.coarse.points());
  EXPECT_EQ(r.geometry.weights(), s.coarse.weights());
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(r.geometry.knots(d).knots(), s.coarse.knots(d).knots());
    EXPECT_EQ(r.iga->knots(d).knots(), s.fine.knots(d).knots());
    EXPECT_EQ(r.iga->degree(d), s.fine.degree(d));
  }

  const SolutionSampler sampler(r);
  for (const Eigen::Vector3d& xi :
       {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.77, 0.5, 0.05),
        Eigen::Vector3d(0.5, 0.93, 0.8)}) {
    const Eigen::Vector3d X = s.coarse.evaluate(xi);
    const Eigen::Vector3d exact = 2.0 * A * X + b;
    EXPECT_LT((*sampler.at_parameter(xi, 1) - exact).norm(), 1e-16) << xi.transpose();
    const std::optional<Eigen::Vector3d> at_X = sampler.at_point(X, 1);
    ASSERT_TRUE(at_X.has_value()) << X.transpose();
    EXPECT_LT((*at_X - exact).norm(), 1e-15) << X.transpose();
  }
  EXPECT_FALSE(sampler.at_point(Eigen::Vector3d(0.02, 0.0, 0.025), 0).has_value());  // outside
  EXPECT_THROW(sampler.at_parameter(Eigen::Vector3d(0.5, 0.5, 0.5), 2), std::out_of_range);
}

TEST(SolutionFile, BadStepsAreRefusedAndKeepTheFileValid) {
  const std::filesystem::path dir = fresh_directory("bad");
  const Solids s = barrel_solids();
  SolutionWriter writer(dir / "solution.h5", s.coarse, s.fine);
  DisplacementRows u = DisplacementRows::Zero(s.fine.num_control_points(), 3);
  writer.write_step(0.5, u);
  EXPECT_THROW(writer.write_step(0.5, u), std::invalid_argument);  // time does not increase
  EXPECT_THROW(writer.write_step(0.6, DisplacementRows::Zero(3, 3)), std::invalid_argument);
  u(7, 1) = std::nan("");
  try {
    writer.write_step(0.7, u);
    FAIL() << "a NaN must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("control point 7"), std::string::npos) << e.what();
  }
  const StoredSolution r = read_solution(dir / "solution.h5");
  EXPECT_EQ(r.times, std::vector<double>{0.5});
}

TEST(SolutionFile, MissingOrForeignFilesAreNamed) {
  const std::filesystem::path dir = fresh_directory("missing");
  try {
    read_solution(dir / "solution.h5");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
  testing_util::write_text(dir / "not_hdf5.h5", "plain text\n");
  EXPECT_THROW(read_solution(dir / "not_hdf5.h5"), std::runtime_error);
}

}  // namespace
}  // namespace isomuscle::io
