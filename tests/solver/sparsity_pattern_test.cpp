// Sparsity pattern, scatter assembly against a dense reference, element colouring and the
// deterministic parallel assembly (1 and 2 OpenMP threads bitwise equal).
#include "solver/sparsity_pattern.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include "solver/element_colouring.hpp"
#include "tests/solver/elasticity_fixture.hpp"

namespace isomuscle::solver {
namespace {

// Random elements of 2 ... 6 DOFs over n free DOFs, with prescribed entries and repeated DOFs.
ElementDofs random_elements(int n, int n_elements, std::mt19937& rng) {
  std::uniform_int_distribution<int> size(2, 6);
  std::uniform_int_distribution<int> dof(-1, n - 1);
  ElementDofs elements;
  for (int e = 0; e < n_elements; ++e) {
    std::vector<int> dofs(static_cast<std::size_t>(size(rng)));
    for (int& d : dofs) {
      d = dof(rng);
    }
    if (e % 7 == 3) {
      dofs.back() = dofs.front();  // a repeated DOF, as for merged control points
    }
    elements.add_element(dofs);
  }
  // Every DOF in at least one element.
  for (int i = 0; i + 1 < n; i += 2) {
    const std::vector<int> pair{i, i + 1};
    elements.add_element(pair);
  }
  elements.add_element(std::vector<int>{n - 1});
  return elements;
}

std::vector<Eigen::MatrixXd> random_matrices(const ElementDofs& elements, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::MatrixXd> matrices;
  for (int e = 0; e < elements.n_elements(); ++e) {
    Eigen::MatrixXd ke(elements.size(e), elements.size(e));
    for (Eigen::Index k = 0; k < ke.size(); ++k) {
      ke.data()[k] = value(rng);
    }
    matrices.push_back(ke);
  }
  return matrices;
}

// K = sum_e P_e^T K_e P_e, dense.
Eigen::MatrixXd dense_reference(const ElementDofs& elements,
                                const std::vector<Eigen::MatrixXd>& matrices, int n) {
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (int e = 0; e < elements.n_elements(); ++e) {
    const auto dofs = elements.dofs(e);
    for (std::size_t a = 0; a < dofs.size(); ++a) {
      for (std::size_t b = 0; b < dofs.size(); ++b) {
        if (dofs[a] >= 0 && dofs[b] >= 0) {
          k(dofs[a], dofs[b]) +=
              matrices[e](static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
        }
      }
    }
  }
  return k;
}

// Pairs (i, j) coupled by some element, restricted to the stored triangle.
std::set<std::pair<int, int>> coupled_pairs(const ElementDofs& elements, MatrixStorage storage) {
  std::set<std::pair<int, int>> pairs;
  for (int e = 0; e < elements.n_elements(); ++e) {
    for (int i : elements.dofs(e)) {
      for (int j : elements.dofs(e)) {
        if (i >= 0 && j >= 0 && (storage == MatrixStorage::Full || i <= j)) {
          pairs.insert({i, j});
        }
      }
    }
  }
  return pairs;
}

class PatternAssembly : public ::testing::TestWithParam<std::tuple<MatrixStorage, ScatterMode>> {};

TEST_P(PatternAssembly, ScatterEqualsDenseReference) {
  const auto [storage, mode] = GetParam();
  std::mt19937 rng(12345);
  const int n = 60;
  const ElementDofs elements = random_elements(n, 150, rng);
  const std::vector<Eigen::MatrixXd> matrices = random_matrices(elements, rng);
  const SparsityPattern pattern(elements, n, storage, mode);

  // The pattern holds exactly the coupled pairs of the stored triangle.
  SparseMatrix k = pattern.make_matrix();
  std::set<std::pair<int, int>> stored;
  for (int j = 0; j < k.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(k, j); it; ++it) {
      stored.insert({static_cast<int>(it.row()), static_cast<int>(it.col())});
    }
  }
  EXPECT_EQ(stored, coupled_pairs(elements, storage));
  EXPECT_TRUE(pattern.matches(k));

  for (int e = 0; e < elements.n_elements(); ++e) {
    pattern.add_element_matrix(e, matrices[e], k);
  }
  const Eigen::MatrixXd reference = dense_reference(elements, matrices, n);
  const Eigen::MatrixXd assembled = Eigen::MatrixXd(k);
  const Eigen::MatrixXd expected = storage == MatrixStorage::Upper
                                       ? Eigen::MatrixXd(reference.triangularView<Eigen::Upper>())
                                       : reference;
  EXPECT_LE((assembled - expected).norm(), 1e-13 * expected.norm());
}

INSTANTIATE_TEST_SUITE_P(
    StorageAndMode, PatternAssembly,
    ::testing::Combine(::testing::Values(MatrixStorage::Upper, MatrixStorage::Full),
                       ::testing::Values(ScatterMode::Stored, ScatterMode::Search)));

TEST(SparsityPattern, StoredAndSearchScatterAreBitwiseEqual) {
  const testing::ElasticityGrid grid{4, 2};
  int n_free = 0;
  const ElementDofs elements = testing::elasticity_dofs(grid, n_free);
  const SparsityPattern stored(elements, n_free, MatrixStorage::Upper, ScatterMode::Stored);
  const SparsityPattern search(elements, n_free, MatrixStorage::Upper, ScatterMode::Search);
  const Eigen::MatrixXd ke = testing::element_stiffness(grid);
  SparseMatrix a = stored.make_matrix();
  SparseMatrix b = search.make_matrix();
  for (int e = 0; e < elements.n_elements(); ++e) {
    const Eigen::MatrixXd scaled = (1.0 + 0.3 * std::sin(e)) * ke;
    stored.add_element_matrix(e, scaled, a);
    search.add_element_matrix(e, scaled, b);
  }
  ASSERT_TRUE(stored.matches(b));
  EXPECT_EQ(0, std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(double) * a.nonZeros()));
  EXPECT_GT(stored.scatter_memory_bytes(), 0u);
  EXPECT_LT(search.scatter_memory_bytes(), 100u);
  EXPECT_THROW(search.scatter(0), std::logic_error);
}

TEST(SparsityPattern, ElasticityPatternHasTheIgaColumnCounts) {
  // An interior control point of a quadratic B-spline grid couples with 5^3 points: 375 entries
  // per column in full storage.
  const testing::ElasticityGrid grid{6, 2};
  const testing::ElasticitySystem full = testing::make_elasticity(grid, MatrixStorage::Full);
  int max_column = 0;
  for (int j = 0; j < full.stiffness.cols(); ++j) {
    max_column = std::max(
        max_column, full.stiffness.outerIndexPtr()[j + 1] - full.stiffness.outerIndexPtr()[j]);
  }
  EXPECT_EQ(max_column, 375);
  const Eigen::MatrixXd dense = Eigen::MatrixXd(full.stiffness);
  EXPECT_LE((dense - dense.transpose()).norm(), 1e-14 * dense.norm());
}

TEST(SparsityPattern, BadInputIsReportedClearly) {
  EXPECT_THROW(ElementDofs(std::vector<std::vector<int>>{{0, -2}}), std::invalid_argument);
  try {
    SparsityPattern(ElementDofs({{0, 1}, {1, 5}}), 3);
    FAIL() << "DOF 5 >= n_free = 3 was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("element 1 holds DOF 5"), std::string::npos)
        << error.what();
  }
  try {
    SparsityPattern(ElementDofs({{0, 1}, {1, 3}}), 4);
    FAIL() << "an unused free DOF was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("free DOF 2 belongs to no element"), std::string::npos)
        << error.what();
  }
  const SparsityPattern pattern(ElementDofs({{0, 1}, {1, 2}}), 3);
  SparseMatrix k = pattern.make_matrix();
  EXPECT_THROW(pattern.add_element_matrix(0, Eigen::Matrix3d::Zero(), k), std::invalid_argument);
  SparseMatrix other(3, 3);
  EXPECT_THROW(pattern.add_element_matrix(0, Eigen::Matrix2d::Zero(), other),
               std::invalid_argument);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(2);
  EXPECT_THROW(pattern.add_element_vector(0, Eigen::Vector2d::Zero(), r), std::invalid_argument);
}

TEST(ElementColouring, NoTwoElementsOfAColourShareADof) {
  std::mt19937 rng(7);
  const ElementDofs elements = random_elements(80, 300, rng);
  const ElementColouring colouring(elements);
  std::vector<int> seen(static_cast<std::size_t>(elements.n_elements()), 0);
  for (int c = 0; c < colouring.n_colours(); ++c) {
    std::set<int> used;
    for (int e : colouring.elements(c)) {
      ++seen[e];
      EXPECT_EQ(colouring.colour_of(e), c);
      std::set<int> own(elements.dofs(e).begin(), elements.dofs(e).end());
      own.erase(kPrescribed);
      for (int dof : own) {
        EXPECT_TRUE(used.insert(dof).second) << "colour " << c << " shares DOF " << dof;
      }
    }
  }
  for (int count : seen) {
    EXPECT_EQ(count, 1);
  }
  // Trilinear hexahedra on a structured grid: greedy lexicographic colouring needs 2^3 colours.
  int n_free = 0;
  const ElementColouring hex(testing::elasticity_dofs({5, 1}, n_free));
  EXPECT_EQ(hex.n_colours(), 8);
}

// Element terms that differ per element: K_e scaled, f_e = K_e * ones.
struct ParallelAssemblyResult {
  SparseMatrix k;
  Eigen::VectorXd r;
};

ParallelAssemblyResult assemble_coloured(const SparsityPattern& pattern,
                                         const ElementColouring& colouring,
                                         const Eigen::MatrixXd& ke, int threads) {
  ParallelAssemblyResult out{pattern.make_matrix(), Eigen::VectorXd::Zero(pattern.size())};
  const int n_threads = resolve_thread_count(threads);
  std::vector<Eigen::MatrixXd> scratch(static_cast<std::size_t>(n_threads), ke);
  std::vector<Eigen::VectorXd> vector_scratch(static_cast<std::size_t>(n_threads));
  const EvaluationStatus status =
      for_each_element_coloured(colouring, threads, [&](int e, int thread) {
        Eigen::MatrixXd& local = scratch[thread];
        local = (1.0 + 0.25 * std::sin(0.7 * e)) * ke;
        vector_scratch[thread].noalias() = local * Eigen::VectorXd::Ones(local.cols());
        pattern.add_element_matrix(e, local, out.k.valuePtr());
        pattern.add_element_vector(e, vector_scratch[thread], out.r);
        return EvaluationStatus::success();
      });
  EXPECT_TRUE(status.ok);
  return out;
}

TEST(ElementColouring, OneAndTwoThreadsAssembleBitwiseEqual) {
  const testing::ElasticityGrid grid{6, 2};
  int n_free = 0;
  ElementDofs elements = testing::elasticity_dofs(grid, n_free);
  const ElementColouring colouring(elements);
  const SparsityPattern pattern(std::move(elements), n_free);
  const Eigen::MatrixXd ke = testing::element_stiffness(grid);

  const ParallelAssemblyResult one = assemble_coloured(pattern, colouring, ke, 1);
  const ParallelAssemblyResult two = assemble_coloured(pattern, colouring, ke, 2);
  ASSERT_EQ(one.k.nonZeros(), two.k.nonZeros());
  EXPECT_EQ(0, std::memcmp(one.k.valuePtr(), two.k.valuePtr(), sizeof(double) * one.k.nonZeros()));
  EXPECT_EQ(0, std::memcmp(one.r.data(), two.r.data(), sizeof(double) * one.r.size()));

  // And both equal the plain serial loop to round-off.
  SparseMatrix serial = pattern.make_matrix();
  Eigen::VectorXd serial_r = Eigen::VectorXd::Zero(n_free);
  for (int e = 0; e < pattern.elements().n_elements(); ++e) {
    const Eigen::MatrixXd local = (1.0 + 0.25 * std::sin(0.7 * e)) * ke;
    pattern.add_element_matrix(e, local, serial);
    const Eigen::VectorXd fe = local * Eigen::VectorXd::Ones(local.cols());
    pattern.add_element_vector(e, fe, serial_r);
  }
  const Eigen::VectorXd values_one =
      Eigen::Map<const Eigen::VectorXd>(one.k.valuePtr(), one.k.nonZeros());
  const Eigen::VectorXd values_serial =
      Eigen::Map<const Eigen::VectorXd>(serial.valuePtr(), serial.nonZeros());
  EXPECT_LE((values_one - values_serial).norm(), 1e-12 * values_serial.norm());
  EXPECT_LE((one.r - serial_r).norm(), 1e-12 * serial_r.norm());
}

TEST(ElementColouring, FailuresAndExceptionsAreReportedDeterministically) {
  int n_free = 0;
  const ElementDofs elements = testing::elasticity_dofs({4, 1}, n_free);
  const ElementColouring colouring(elements);
  // Elements >= 20 fail: the reported one is the lowest failing element of the first colour that
  // has a failing element, whatever the thread count.
  int expected = -1;
  for (int c = 0; c < colouring.n_colours() && expected < 0; ++c) {
    for (int e : colouring.elements(c)) {
      if (e >= 20) {
        expected = e;
        break;
      }
    }
  }
  for (int threads : {1, 2}) {
    const EvaluationStatus status = for_each_element_coloured(colouring, threads, [](int e, int) {
      return e >= 20 ? EvaluationStatus::failure("element " + std::to_string(e) + ": J <= 0")
                     : EvaluationStatus::success();
    });
    EXPECT_FALSE(status.ok);
    EXPECT_EQ(status.message, "element " + std::to_string(expected) + ": J <= 0");
  }
  EXPECT_THROW(for_each_element_coloured(colouring, 2,
                                         [](int e, int) -> EvaluationStatus {
                                           if (e == 3) {
                                             throw std::runtime_error("element 3 broke");
                                           }
                                           return EvaluationStatus::success();
                                         }),
               std::runtime_error);
  EXPECT_THROW(resolve_thread_count(-1), std::invalid_argument);
}

}  // namespace
}  // namespace isomuscle::solver
