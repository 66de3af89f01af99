// lowest_modes: the lowest eigenpairs of K phi = lambda W phi against Eigen's dense generalised
// solver, for a positive definite K (shift 0) and for K made indefinite by subtracting a multiple
// of W (the negative eigenvalues of an unstable equilibrium); bad input.
#include "solver/lowest_modes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <stdexcept>

#include "solver/setting_error.hpp"
#include "tests/solver/elasticity_fixture.hpp"

namespace isomuscle::solver {
namespace {

// Positive weights between 0.5 and 2 (a lumped mass of uneven elements).
Eigen::VectorXd random_weights(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(0.5, 2.0);
  Eigen::VectorXd w(n);
  for (Eigen::Index i = 0; i < n; ++i)
    w[i] = value(rng);
  return w;
}

// K - s W for a K given by its upper triangle.
SparseMatrix minus_weighted(const SparseMatrix& k, const Eigen::VectorXd& w, double s) {
  SparseMatrix d(k.rows(), k.cols());
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index i = 0; i < k.rows(); ++i)
    t.emplace_back(static_cast<int>(i), static_cast<int>(i), s * w[i]);
  d.setFromTriplets(t.begin(), t.end());
  SparseMatrix out = k - d;
  out.makeCompressed();
  return out;
}

// The dense symmetric matrix of a sparse one given by its upper triangle.
Eigen::MatrixXd dense_symmetric(const SparseMatrix& upper) {
  return Eigen::MatrixXd(SparseMatrix(upper.selfadjointView<Eigen::Upper>()));
}

// Checks the lowest `count` pairs against the dense solution of the same pencil.
void expect_dense_agreement(const SparseMatrix& k_upper, const Eigen::VectorXd& w,
                            const LowestModes& modes, int count) {
  ASSERT_TRUE(modes.ok) << modes.message;
  ASSERT_EQ(modes.eigenvalues.size(), count);
  const Eigen::MatrixXd k = dense_symmetric(k_upper);
  const Eigen::MatrixXd wd = w.asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(k, wd);
  ASSERT_EQ(dense.info(), Eigen::Success);
  const double scale = dense.eigenvalues().cwiseAbs().maxCoeff();
  for (int i = 0; i < count; ++i) {
    EXPECT_NEAR(modes.eigenvalues[i], dense.eigenvalues()[i], 1e-9 * scale) << "pair " << i;
    if (i > 0) {
      EXPECT_LE(modes.eigenvalues[i - 1], modes.eigenvalues[i]);
    }
    // W-normalised, and the same vector up to sign (the pairs checked here are simple).
    const Eigen::VectorXd phi = modes.vectors.col(i);
    EXPECT_NEAR(phi.dot(w.cwiseProduct(phi)), 1.0, 1e-10);
    const Eigen::VectorXd ref = dense.eigenvectors().col(i);
    const double cosine =
        std::abs(phi.dot(w.cwiseProduct(ref))) / std::sqrt(ref.dot(w.cwiseProduct(ref)));
    EXPECT_NEAR(cosine, 1.0, 1e-8) << "pair " << i;
  }
  EXPECT_LT(modes.max_residual, 1e-8 * scale);
}

TEST(LowestModes, PositiveDefiniteStiffnessNeedsNoShift) {
  const testing::ElasticitySystem system = testing::make_elasticity({4, 1});  // 300 unknowns
  const Eigen::VectorXd w = random_weights(system.stiffness.rows(), 1);
  const LowestModes modes = lowest_modes(system.stiffness, w, {.count = 4});
  EXPECT_EQ(modes.shift, 0.0);
  EXPECT_EQ(modes.factorizations, 1);
  EXPECT_EQ(modes.negative(), 0);
  expect_dense_agreement(system.stiffness, w, modes, 4);
}

TEST(LowestModes, FindsTheNegativeEigenvaluesOfAnIndefiniteMatrix) {
  const testing::ElasticitySystem system = testing::make_elasticity({4, 2});  // B-spline pattern
  const Eigen::Index n = system.stiffness.rows();
  const Eigen::VectorXd w = random_weights(n, 2);
  // Move the spectrum down between its 2nd and 3rd eigenvalues: two negative eigenvalues, the
  // second of them close to zero, as just past a loss of stability.
  const Eigen::MatrixXd k = dense_symmetric(system.stiffness);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(
      k, Eigen::MatrixXd(w.asDiagonal()), Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& lambda = dense.eigenvalues();
  const double s = lambda[1] + 0.01 * (lambda[2] - lambda[1]);
  const SparseMatrix indefinite = minus_weighted(system.stiffness, w, s);
  const LowestModes modes = lowest_modes(indefinite, w, {.count = 3});
  expect_dense_agreement(indefinite, w, modes, 3);
  EXPECT_EQ(modes.negative(), 2);
  EXPECT_LT(modes.shift, modes.eigenvalues[0]);  // the shift lies below the spectrum
  // Bisected to within 10^(1/8) of the smallest eigenvalue.
  EXPECT_LT(modes.shift / modes.eigenvalues[0], std::pow(10.0, 0.125) * 1.0001);
}

TEST(LowestModes, RejectsBadInput) {
  const testing::ElasticitySystem system = testing::make_elasticity({2, 1});
  const Eigen::Index n = system.stiffness.rows();
  EXPECT_THROW(lowest_modes(system.stiffness, Eigen::VectorXd::Ones(n - 1)), std::invalid_argument);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(n);
  w[3] = 0.0;
  EXPECT_THROW(lowest_modes(system.stiffness, w), std::invalid_argument);
  EXPECT_THROW(lowest_modes(system.stiffness, Eigen::VectorXd::Ones(n), {.count = 0}),
               SettingError);
  // A matrix no shift of the ladder can make positive definite is reported, not thrown.
  const SparseMatrix hopeless = minus_weighted(system.stiffness, Eigen::VectorXd::Ones(n), 1e9);
  const LowestModes modes =
      lowest_modes(hopeless, Eigen::VectorXd::Ones(n), {.count = 2, .shift_attempts = 3});
  EXPECT_FALSE(modes.ok);
  EXPECT_NE(modes.message.find("no shift"), std::string::npos) << modes.message;
}

}  // namespace
}  // namespace isomuscle::solver
