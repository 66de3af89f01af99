// CHOLMOD Cholesky with UMFPACK fallback: residual of an SPD elasticity solve (~10^4 unknowns),
// symbolic analysis reused, indefinite matrix -> LU fallback recorded, singular -> failure.
#include "solver/linear_solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/blas_threads.hpp"
#include "solver/setting_error.hpp"
#include "tests/solver/elasticity_fixture.hpp"

namespace isomuscle::solver {
namespace {

Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    v[i] = value(rng);
  }
  return v;
}

// |A x - b| / |b| with A given by its upper triangle (or in full).
double relative_residual(const SparseMatrix& a, MatrixStorage storage, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b) {
  const Eigen::VectorXd ax = storage == MatrixStorage::Upper
                                 ? Eigen::VectorXd(a.selfadjointView<Eigen::Upper>() * x)
                                 : Eigen::VectorXd(a * x);
  return (ax - b).norm() / b.norm();
}

TEST(LinearSolver, CholeskySolvesElasticityAndReusesTheAnalysis) {
  // 15^3 trilinear hexahedra: 11520 free DOFs.
  const testing::ElasticitySystem system = testing::make_elasticity({15, 1});
  SparseMatrix k = system.stiffness;
  ASSERT_EQ(k.rows(), 11520);
  LinearSolver solver;
  for (int call = 0; call < 3; ++call) {
    // A different matrix with the same pattern each call (a Newton iteration's new tangent).
    Eigen::Map<Eigen::VectorXd>(k.valuePtr(), k.nonZeros()) =
        (1.0 + 0.5 * call) *
        Eigen::Map<const Eigen::VectorXd>(system.stiffness.valuePtr(), k.nonZeros());
    const FactorizationReport report = solver.factorize(k);
    ASSERT_TRUE(report.ok) << report.message;
    EXPECT_EQ(report.method, LinearMethod::Cholesky);
    EXPECT_FALSE(report.fell_back);
    EXPECT_GT(report.rcond, 0.0);
    EXPECT_LT(report.rcond, 1.0);
    const Eigen::VectorXd b = random_vector(k.rows(), 10 + call);
    Eigen::VectorXd x;
    solver.solve(b, x);
    EXPECT_LE(relative_residual(k, MatrixStorage::Upper, x, b), 1e-10);
  }
  const LinearSolverStatistics& stats = solver.statistics();
  std::cout << "n = " << k.rows() << ", nnz(upper) = " << k.nonZeros()
            << ", nnz(L) = " << solver.cholesky().factor_nonzeros() << " ("
            << solver.cholesky().ordering_used() << "), symbolic " << stats.time.symbolic
            << " s, 3 numeric " << stats.time.numeric << " s, 3 solves " << stats.time.solve
            << " s\n";
  EXPECT_EQ(stats.symbolic_analyses, 1);
  EXPECT_EQ(stats.pattern_changes, 0);
  EXPECT_EQ(stats.cholesky_factorizations, 3);
  EXPECT_EQ(stats.cholesky_failures, 0);
  EXPECT_EQ(stats.lu_factorizations, 0);
  EXPECT_EQ(stats.solves, 3);
  EXPECT_GT(stats.time.symbolic, 0.0);
  EXPECT_GT(stats.time.numeric, 0.0);
  EXPECT_GT(stats.time.solve, 0.0);
  EXPECT_GT(solver.cholesky().factor_nonzeros(), static_cast<double>(k.nonZeros()));
  EXPECT_NE(solver.cholesky().ordering_used(), "none");

  // A different pattern is analysed again.
  const testing::ElasticitySystem other = testing::make_elasticity({4, 2});
  ASSERT_TRUE(solver.factorize(other.stiffness).ok);
  EXPECT_EQ(solver.statistics().symbolic_analyses, 2);
  EXPECT_EQ(solver.statistics().pattern_changes, 1);
}

TEST(LinearSolver, FullStorageSymmetricMatrixGivesTheSameSolution) {
  const testing::ElasticitySystem upper = testing::make_elasticity({6, 2});
  const testing::ElasticitySystem full = testing::make_elasticity({6, 2}, MatrixStorage::Full);
  LinearSolver upper_solver;
  LinearSolver full_solver(LinearSolverSettings{MatrixStorage::Full, LinearMethod::Cholesky,
                                                IndefiniteResponse::Lu, CholeskyOrdering::Amd});
  ASSERT_TRUE(upper_solver.factorize(upper.stiffness).ok);
  ASSERT_TRUE(full_solver.factorize(full.stiffness).ok);
  EXPECT_EQ(full_solver.cholesky().ordering_used(), "AMD");
  const Eigen::VectorXd b = random_vector(upper.stiffness.rows(), 3);
  Eigen::VectorXd x_upper;
  Eigen::VectorXd x_full;
  upper_solver.solve(b, x_upper);
  full_solver.solve(b, x_full);
  EXPECT_LE(relative_residual(full.stiffness, MatrixStorage::Full, x_full, b), 1e-10);
  EXPECT_LE((x_upper - x_full).norm(), 1e-9 * x_upper.norm());
}

TEST(LinearSolver, LuAloneSolvesAnUpperStoredSymmetricMatrix) {
  // The scene's "umfpack" choice: LU of the upper-stored tangent, expanded to both triangles.
  const testing::ElasticitySystem system = testing::make_elasticity({6, 1});
  LinearSolverSettings settings;
  settings.method = LinearMethod::Lu;
  LinearSolver solver(settings);
  for (int call = 0; call < 2; ++call) {
    const FactorizationReport report = solver.factorize(system.stiffness);
    ASSERT_TRUE(report.ok) << report.message;
    EXPECT_EQ(report.method, LinearMethod::Lu);
    EXPECT_FALSE(report.fell_back);
    const Eigen::VectorXd b = random_vector(system.stiffness.rows(), 21 + call);
    Eigen::VectorXd x;
    solver.solve(b, x);
    EXPECT_LE(relative_residual(system.stiffness, MatrixStorage::Upper, x, b), 1e-10);
  }
  EXPECT_EQ(solver.statistics().symbolic_analyses, 0);
  EXPECT_EQ(solver.statistics().lu_symbolic_analyses, 1);
  EXPECT_EQ(solver.statistics().lu_factorizations, 2);
  EXPECT_EQ(solver.statistics().lu_fallbacks, 0);
}

TEST(LinearSolver, IndefiniteMatrixFallsBackToLuAndStillSolves) {
  const testing::ElasticitySystem system = testing::make_elasticity({8, 1});
  SparseMatrix k = system.stiffness;
  LinearSolver solver;
  ASSERT_TRUE(solver.factorize(k).ok);
  // K - sigma I with sigma between the eigenvalues: symmetric indefinite (e.g. past a limit point).
  testing::shift_diagonal(k, 0.5 * k.diagonal().mean());
  const FactorizationReport report = solver.factorize(k);
  ASSERT_TRUE(report.ok) << report.message;
  EXPECT_EQ(report.method, LinearMethod::Lu);
  EXPECT_TRUE(report.fell_back);
  EXPECT_NE(report.message.find("not positive definite"), std::string::npos) << report.message;
  EXPECT_GT(report.rcond, 0.0);
  const Eigen::VectorXd b = random_vector(k.rows(), 5);
  Eigen::VectorXd x;
  solver.solve(b, x);
  EXPECT_LE(relative_residual(k, MatrixStorage::Upper, x, b), 1e-10);
  // The Cholesky factor is usable again after the failure (same pattern, no new analysis).
  ASSERT_TRUE(solver.factorize(system.stiffness).ok);
  EXPECT_EQ(solver.last_report().method, LinearMethod::Cholesky);
  solver.solve(b, x);
  EXPECT_LE(relative_residual(system.stiffness, MatrixStorage::Upper, x, b), 1e-10);

  const LinearSolverStatistics& stats = solver.statistics();
  EXPECT_EQ(stats.cholesky_factorizations, 3);
  EXPECT_EQ(stats.cholesky_failures, 1);
  EXPECT_EQ(stats.lu_fallbacks, 1);
  EXPECT_EQ(stats.lu_factorizations, 1);
  EXPECT_EQ(stats.lu_symbolic_analyses, 1);
  EXPECT_EQ(stats.symbolic_analyses, 1);
  EXPECT_EQ(stats.failures, 0);
}

// Releasing the factorisation between uses (Newton's solver at the end of each solve, the
// predictor's after its solve) frees the numeric factor and keeps the symbolic analysis: solve()
// refuses until the next factorize, which needs no new analysis and gives the same solution,
// bitwise, for Cholesky and for the LU fallback alike.
TEST(LinearSolver, ReleasedFactorisationIsRefusedUntilTheNextAndChangesNothing) {
  const testing::ElasticitySystem system = testing::make_elasticity({8, 1});
  SparseMatrix indefinite = system.stiffness;
  testing::shift_diagonal(indefinite, 0.5 * indefinite.diagonal().mean());
  const Eigen::VectorXd b = random_vector(system.stiffness.rows(), 9);
  LinearSolver solver;
  for (const SparseMatrix* k : std::vector<const SparseMatrix*>{&system.stiffness, &indefinite}) {
    ASSERT_TRUE(solver.factorize(*k).ok);
    const LinearMethod method = solver.last_report().method;
    Eigen::VectorXd before, after;
    solver.solve(b, before);
    solver.release_factorization();
    EXPECT_FALSE(solver.cholesky().factorized());
    EXPECT_FALSE(solver.lu().factorized());
    EXPECT_TRUE(solver.cholesky().analyzed());
    EXPECT_THROW(solver.solve(b, after), std::logic_error);
    solver.release_factorization();  // twice is harmless
    ASSERT_TRUE(solver.factorize(*k).ok);
    EXPECT_EQ(solver.last_report().method, method);
    solver.solve(b, after);
    EXPECT_EQ(after, before);
  }
  EXPECT_EQ(solver.last_report().method, LinearMethod::Lu);
  EXPECT_EQ(solver.statistics().symbolic_analyses, 1);
  EXPECT_EQ(solver.statistics().lu_symbolic_analyses, 1);
  // CHOLMOD alone: the symbolic factor left by the release is factorised again.
  CholmodCholesky cholesky;
  cholesky.analyze(system.stiffness);
  ASSERT_TRUE(cholesky.factorize(system.stiffness).ok);
  Eigen::VectorXd x1, x2;
  cholesky.solve(b, x1);
  cholesky.release_numeric();
  EXPECT_FALSE(cholesky.factorized());
  EXPECT_THROW(cholesky.solve(b, x2), std::logic_error);
  ASSERT_TRUE(cholesky.factorize(system.stiffness).ok);
  cholesky.solve(b, x2);
  EXPECT_EQ(x1, x2);
}

// The shift response factorises K + tau mean|K_ii| I for the first tau of its sequence that makes
// the matrix positive definite (the one before it does not), solves with that matrix, and starts
// the next indefinite matrix one step of the sequence lower (Levenberg-Marquardt's relaxation).
TEST(LinearSolver, ShiftResponseFactorisesTheFirstSufficientShiftAndRelaxesIt) {
  const testing::ElasticitySystem system = testing::make_elasticity({8, 1});
  const SparseMatrix k = testing::below_mean_diagonal(system.stiffness, 0.02);
  LinearSolverSettings settings;
  settings.indefinite = IndefiniteResponse::Shift;
  LinearSolver solver(settings);
  const FactorizationReport report = solver.factorize(k);
  ASSERT_TRUE(report.ok) << report.message;
  EXPECT_EQ(report.method, LinearMethod::Cholesky);
  EXPECT_TRUE(report.fell_back);
  EXPECT_NE(report.message.find("not positive definite"), std::string::npos) << report.message;
  // The matrix was shifted by 0.02 mean(diag) below an SPD one: tau = 0.1 is the first power of
  // ten in the sequence 1e-9, 1e-8, ... that restores positive definiteness (0.01 cannot, as the
  // stiffness's smallest eigenvalue is far below 0.01 mean(diag)).
  EXPECT_NEAR(report.shift, 0.1, 1e-12);
  const double scale = k.diagonal().cwiseAbs().mean();
  CholmodCholesky check;
  check.analyze(k);
  EXPECT_TRUE(check.factorize(k, report.shift * scale).ok);
  EXPECT_FALSE(check.factorize(k, 0.1 * report.shift * scale).ok);

  // solve() solves with the shifted matrix.
  const Eigen::VectorXd b = random_vector(k.rows(), 23);
  Eigen::VectorXd x;
  solver.solve(b, x);
  SparseMatrix shifted = k;
  testing::shift_diagonal(shifted, -report.shift * scale);
  EXPECT_LE(relative_residual(shifted, MatrixStorage::Upper, x, b), 1e-10);
  // A descent direction of the quadratic form: b . x > 0 (x = (K + beta I)^-1 b, SPD).
  EXPECT_GT(b.dot(x), 0.0);

  const int attempts_first = solver.statistics().cholesky_factorizations;  // 1 + 9 shifts
  EXPECT_EQ(attempts_first, 1 + 9);
  // The same matrix again: the sequence starts at tau / 10 (fails), then tau.
  ASSERT_TRUE(solver.factorize(k).ok);
  EXPECT_NEAR(solver.last_report().shift, 0.1, 1e-12);
  EXPECT_EQ(solver.statistics().cholesky_factorizations, attempts_first + 3);
  // A positive definite matrix is factorised unshifted and resets the relaxation.
  ASSERT_TRUE(solver.factorize(system.stiffness).ok);
  EXPECT_EQ(solver.last_report().shift, 0.0);
  EXPECT_FALSE(solver.last_report().fell_back);
  const LinearSolverStatistics& stats = solver.statistics();
  EXPECT_EQ(stats.shifted_factorizations, 2);
  // Two indefinite matrices; their failed shifts 1e-9 ... 1e-2 and then 1e-2 are counted apart.
  EXPECT_EQ(stats.cholesky_failures, 2);
  EXPECT_EQ(stats.failed_shifts, 8 + 1);
  EXPECT_DOUBLE_EQ(stats.max_shift, report.shift);
  EXPECT_EQ(stats.lu_factorizations, 0);
  EXPECT_EQ(stats.failures, 0);
  EXPECT_GT(stats.time.shifted, 0.0);
  EXPECT_LE(stats.time.shifted, stats.time.numeric);
}

// When no shift of the sequence suffices (here: a single attempt, far too small) the factorisation
// fails with the largest tau tried, and solve() has nothing to solve with.
TEST(LinearSolver, ShiftResponseFailsNamingTheLargestShiftTried) {
  const SparseMatrix k =
      testing::below_mean_diagonal(testing::make_elasticity({6, 1}).stiffness, 0.5);
  LinearSolverSettings settings;
  settings.indefinite = IndefiniteResponse::Shift;
  settings.shift_attempts = 2;
  LinearSolver solver(settings);
  const FactorizationReport report = solver.factorize(k);
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("2 shifts up to tau = 1e-08"), std::string::npos) << report.message;
  Eigen::VectorXd x;
  EXPECT_THROW(solver.solve(Eigen::VectorXd::Ones(k.rows()), x), std::logic_error);
  EXPECT_EQ(solver.statistics().failures, 1);
}

// The LU fallback of an upper-stored symmetric matrix factorises it with UMFPACK's symmetric
// strategy in CHOLMOD's order, so its L + U hold about twice the Cholesky factor's nonzeros. Before
// 2026-12-04 UMFPACK analysed an unfilled expansion, saw no diagonal, took its unsymmetric
// strategy, and on the DAO's tangent (27509 unknowns) had not finished after 16 minutes.
TEST(LinearSolver, LuFallbackKeepsTheFillOfTheSymmetricPattern) {
  const SparseMatrix k =
      testing::below_mean_diagonal(testing::make_elasticity({8, 2}).stiffness, 0.02);
  LinearSolver solver;
  const FactorizationReport report = solver.factorize(k);
  ASSERT_TRUE(report.ok) << report.message;
  ASSERT_TRUE(report.fell_back);
  EXPECT_TRUE(solver.lu().symmetric_strategy());
  const double cholesky_nonzeros = solver.cholesky().factor_nonzeros();
  ASSERT_GT(cholesky_nonzeros, 0.0);
  // L + U of a symmetric pivot sequence in the same order: 2 nnz(L) (UMFPACK counts the diagonal
  // in both, as the 3 x 3 case below shows).
  EXPECT_LE(solver.lu().factor_nonzeros(), 2.0 * cholesky_nonzeros) << cholesky_nonzeros;
  EXPECT_GE(solver.lu().factor_nonzeros(), 2.0 * cholesky_nonzeros - 1.5 * k.rows());
  const Eigen::VectorXd b = random_vector(k.rows(), 17);
  Eigen::VectorXd x;
  solver.solve(b, x);
  EXPECT_LE(relative_residual(k, MatrixStorage::Upper, x, b), 1e-10);
}

TEST(UmfpackLu, AColumnOrderThatIsNotAPermutationIsRefused) {
  SparseMatrix a(3, 3);
  for (int i = 0; i < 3; ++i) {
    a.insert(i, i) = 1.0 + i;
  }
  a.makeCompressed();
  UmfpackLu lu;
  for (const std::vector<int>& order :
       {std::vector<int>{0, 1}, std::vector<int>{0, 1, 1}, std::vector<int>{0, 1, 3}}) {
    try {
      lu.analyze(a, LuAnalysisOptions{false, order});
      ADD_FAILURE() << "order of size " << order.size() << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("not a permutation of 0..2"), std::string::npos)
          << e.what();
    }
  }
  lu.analyze(a, LuAnalysisOptions{true, {2, 0, 1}});
  ASSERT_TRUE(lu.factorize(a).ok);
  Eigen::VectorXd x;
  lu.solve(Eigen::Vector3d(1.0, 2.0, 3.0), x);
  EXPECT_NEAR(x[2], 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(lu.factor_nonzeros(), 6.0);  // L and U each hold the diagonal
}

TEST(LinearSolver, WithoutFallbackAnIndefiniteMatrixIsAFailure) {
  SparseMatrix k(2, 2);
  k.insert(0, 0) = 1.0;
  k.insert(0, 1) = 2.0;
  k.insert(1, 1) = 1.0;
  k.makeCompressed();
  LinearSolverSettings settings;
  settings.indefinite = IndefiniteResponse::Fail;
  LinearSolver solver(settings);
  const FactorizationReport report = solver.factorize(k);
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("fail, no LU or shifted factorisation tried"), std::string::npos)
      << report.message;
  Eigen::VectorXd x;
  EXPECT_THROW(solver.solve(Eigen::Vector2d(1.0, 0.0), x), std::logic_error);
  EXPECT_EQ(solver.statistics().failures, 1);
}

TEST(LinearSolver, SingularMatrixIsAFailureWithAMessage) {
  // [[1, 1], [1, 1]]: Cholesky stops at the zero pivot, LU finds the matrix singular.
  SparseMatrix k(2, 2);
  k.insert(0, 0) = 1.0;
  k.insert(0, 1) = 1.0;
  k.insert(1, 1) = 1.0;
  k.makeCompressed();
  LinearSolver solver;
  const FactorizationReport report = solver.factorize(k);
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("singular"), std::string::npos) << report.message;
  EXPECT_EQ(solver.statistics().cholesky_failures, 1);
  EXPECT_EQ(solver.statistics().failures, 1);
  Eigen::VectorXd x;
  EXPECT_THROW(solver.solve(Eigen::Vector2d(1.0, 0.0), x), std::logic_error);
}

TEST(LinearSolver, NonSymmetricMatrixIsSolvedByLu) {
  // A convection–diffusion-like tridiagonal matrix, stored in full.
  const int n = 200;
  SparseMatrix a(n, n);
  for (int i = 0; i < n; ++i) {
    a.insert(i, i) = 2.0;
    if (i > 0) {
      a.insert(i, i - 1) = -1.3;
    }
    if (i + 1 < n) {
      a.insert(i, i + 1) = -0.7;
    }
  }
  a.makeCompressed();
  LinearSolver solver(LinearSolverSettings{MatrixStorage::Full, LinearMethod::Lu,
                                           IndefiniteResponse::Lu, CholeskyOrdering::Default});
  const FactorizationReport report = solver.factorize(a);
  ASSERT_TRUE(report.ok) << report.message;
  EXPECT_EQ(report.method, LinearMethod::Lu);
  EXPECT_FALSE(report.fell_back);
  const Eigen::VectorXd b = random_vector(n, 9);
  Eigen::VectorXd x;
  solver.solve(b, x);
  EXPECT_LE(relative_residual(a, MatrixStorage::Full, x, b), 1e-12);
  EXPECT_EQ(solver.statistics().symbolic_analyses, 0);
  EXPECT_EQ(solver.statistics().lu_symbolic_analyses, 1);
}

// The BLAS under CHOLMOD is Debian's OpenBLAS here (install-deps.sh): its thread count can be
// set and read back, and a solver made with blas_threads = 1 leaves it at one.
TEST(LinearSolver, BlasThreadsAreSetWhenTheBlasIsOpenBlas) {
  if (blas_threads() == 0)
    GTEST_SKIP() << "the loaded BLAS is not OpenBLAS: nothing to set";
  ASSERT_TRUE(set_blas_threads(2));
  EXPECT_EQ(blas_threads(), 2);
  LinearSolverSettings settings;
  settings.blas_threads = 1;
  const LinearSolver solver(settings);
  EXPECT_EQ(blas_threads(), 1);
  EXPECT_FALSE(set_blas_threads(0));
  EXPECT_EQ(blas_threads(), 1);
  settings.blas_threads = -1;
  EXPECT_THROW(LinearSolver{settings}, SettingError);
}

TEST(LinearSolver, BadInputIsReportedClearly) {
  // Non-finite entries: a failure naming the entry, not a crash.
  SparseMatrix k(2, 2);
  k.insert(0, 0) = 1.0;
  k.insert(1, 1) = std::nan("");
  k.makeCompressed();
  LinearSolver solver;
  const FactorizationReport report = solver.factorize(k);
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.message.find("non-finite entry nan at (1, 1)"), std::string::npos)
      << report.message;

  // Entries below the diagonal with Upper storage.
  SparseMatrix lower(2, 2);
  lower.insert(0, 0) = 2.0;
  lower.insert(1, 0) = 1.0;
  lower.insert(1, 1) = 2.0;
  lower.makeCompressed();
  EXPECT_THROW(LinearSolver().factorize(lower), std::invalid_argument);

  SparseMatrix uncompressed(2, 2);
  uncompressed.insert(0, 0) = 1.0;
  EXPECT_THROW(LinearSolver().factorize(uncompressed), std::invalid_argument);

  try {
    LinearSolver(LinearSolverSettings{MatrixStorage::Upper, LinearMethod::None,
                                      IndefiniteResponse::Lu, CholeskyOrdering::Default});
    FAIL() << "method none was accepted";
  } catch (const SettingError& error) {
    EXPECT_EQ(error.key(), "method");
  }
}

}  // namespace
}  // namespace isomuscle::solver
