// CHOLMOD supernodal Cholesky on 3D elasticity stiffness matrices (tests/solver/
// elasticity_fixture.hpp): symbolic analysis and numeric factorisation time against the number of
// unknowns, for trilinear hexahedra (degree 1) and the quadratic B-spline IGA pattern (degree 2),
// through the raw C API (solver::CholmodCholesky, with a choice of ordering) and through
// Eigen::CholmodSupernodalLLT (same CHOLMOD routines, CHOLMOD's default ordering).
//
// BM_LuFallback: the same matrices shifted to be indefinite (K - 0.02 mean(diag K) I), through
// solver::LinearSolver: the failed Cholesky and UMFPACK's LU that replaces it (symmetric strategy
// in CHOLMOD's order, umfpack_lu.hpp), per Newton iteration that meets an indefinite tangent;
// counters nnz_LU against nnz_L.
// BM_ShiftFallback: the same indefinite matrices with the shift response (Cholesky of K + beta I,
// linear_solver.hpp): the failed Cholesky and the shifted attempts that replace the LU; after the
// first call the sequence starts one step below the last sufficient shift, as it does in a Newton
// solve; counters shift (tau) and attempts (Cholesky factorisations per call, steady state).
//
// Arguments: {elements per side, degree, ordering (0 default, 1 AMD, 2 METIS, 3 NESDIS)}.
// Counters: unknowns, nnz_L (nonzeros of the factor), GFlop (of one numeric factorisation) and
// GFlop/s (against wall time).
#include <benchmark/benchmark.h>

#include <Eigen/CholmodSupport>
#include <map>
#include <utility>

#include "solver/cholmod_cholesky.hpp"
#include "solver/linear_solver.hpp"
#include "tests/solver/elasticity_fixture.hpp"

namespace {

using isomuscle::solver::CholeskyOrdering;
using isomuscle::solver::CholmodCholesky;
using isomuscle::solver::SparseMatrix;

// Upper triangle of the stiffness of an n^3 grid of the given degree, built once per size.
const SparseMatrix& stiffness(int n, int degree) {
  static std::map<std::pair<int, int>, SparseMatrix> cache;
  auto it = cache.find({n, degree});
  if (it == cache.end()) {
    it = cache
             .emplace(std::make_pair(n, degree),
                      isomuscle::solver::testing::make_elasticity({n, degree}).stiffness)
             .first;
  }
  return it->second;
}

CholeskyOrdering ordering(int64_t code) {
  switch (code) {
    case 1:
      return CholeskyOrdering::Amd;
    case 2:
      return CholeskyOrdering::Metis;
    case 3:
      return CholeskyOrdering::Nesdis;
    default:
      return CholeskyOrdering::Default;
  }
}

void set_counters(benchmark::State& state, const SparseMatrix& k, const CholmodCholesky& chol,
                  bool per_second_flops) {
  state.counters["unknowns"] = static_cast<double>(k.rows());
  state.counters["nnz_L"] = chol.factor_nonzeros();
  state.counters["GFlop"] = chol.factor_flops() * 1e-9;
  if (per_second_flops) {
    state.counters["GFlop/s"] = benchmark::Counter(chol.factor_flops() * 1e-9,
                                                   benchmark::Counter::kIsIterationInvariantRate);
  }
}

// Symbolic analysis (ordering, elimination tree, supernodes): once per pattern in a run.
void BM_RawSymbolic(benchmark::State& state) {
  const SparseMatrix& k =
      stiffness(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  CholmodCholesky chol(ordering(state.range(2)));
  for (auto _ : state) {
    chol.analyze(k);
  }
  set_counters(state, k, chol, false);
  state.SetLabel(chol.ordering_used());
}

// Numeric factorisation: once per Newton iteration.
void BM_RawNumeric(benchmark::State& state) {
  const SparseMatrix& k =
      stiffness(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  CholmodCholesky chol(ordering(state.range(2)));
  chol.analyze(k);
  for (auto _ : state) {
    if (!chol.factorize(k).ok) {
      state.SkipWithError("factorisation failed");
      break;
    }
  }
  set_counters(state, k, chol, true);
  state.SetLabel(chol.ordering_used());
}

void BM_EigenSymbolic(benchmark::State& state) {
  const SparseMatrix& k =
      stiffness(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt;
  for (auto _ : state) {
    llt.analyzePattern(k);
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
}

void BM_EigenNumeric(benchmark::State& state) {
  const SparseMatrix& k =
      stiffness(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt;
  llt.analyzePattern(k);
  for (auto _ : state) {
    llt.factorize(k);
    if (llt.info() != Eigen::Success) {
      state.SkipWithError("factorisation failed");
      break;
    }
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
}

// Cholesky attempt and LU fallback of an indefinite matrix: once per Newton iteration past a limit
// point or with a locally indefinite material tangent.
void BM_LuFallback(benchmark::State& state) {
  const SparseMatrix k = isomuscle::solver::testing::below_mean_diagonal(
      stiffness(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))), 0.02);
  isomuscle::solver::LinearSolverSettings settings;
  settings.ordering = ordering(state.range(2));
  isomuscle::solver::LinearSolver solver(settings);
  for (auto _ : state) {
    const isomuscle::solver::FactorizationReport report = solver.factorize(k);
    if (!report.ok || !report.fell_back) {
      state.SkipWithError("no LU fallback");
      break;
    }
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
  state.counters["nnz_L"] = solver.cholesky().factor_nonzeros();
  state.counters["nnz_LU"] = solver.lu().factor_nonzeros();
  state.SetLabel(solver.lu().symmetric_strategy() ? "symmetric" : "unsymmetric");
}

// The same with the shift response: the steady state of one Newton iteration that meets it.
void BM_ShiftFallback(benchmark::State& state) {
  const SparseMatrix k = isomuscle::solver::testing::below_mean_diagonal(
      stiffness(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))), 0.02);
  isomuscle::solver::LinearSolverSettings settings;
  settings.ordering = ordering(state.range(2));
  settings.indefinite = isomuscle::solver::IndefiniteResponse::Shift;
  isomuscle::solver::LinearSolver solver(settings);
  if (!solver.factorize(k).ok) {  // the first call walks the sequence up from shift_initial
    state.SkipWithError("no shifted factorisation");
    return;
  }
  const int before = solver.statistics().cholesky_factorizations;
  for (auto _ : state) {
    const isomuscle::solver::FactorizationReport report = solver.factorize(k);
    if (!report.ok || report.shift <= 0.0) {
      state.SkipWithError("no shifted factorisation");
      break;
    }
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
  state.counters["nnz_L"] = solver.cholesky().factor_nonzeros();
  state.counters["shift"] = solver.last_report().shift;
  state.counters["attempts"] =
      static_cast<double>(solver.statistics().cholesky_factorizations - before) /
      static_cast<double>(state.iterations());
}

// Degree 1: 3.3k, 11.5k, 25k, 49k unknowns; degree 2 (IGA): 4.8k, 11.5k, 22k, 39k unknowns.
void sizes(benchmark::internal::Benchmark* b) {
  for (int n : {10, 15, 20, 25}) {
    b->Args({n, 1, 0});
  }
  for (int n : {10, 14, 18, 22}) {
    b->Args({n, 2, 0});
  }
}

// Orderings compared on one size of each degree.
void orderings(benchmark::internal::Benchmark* b) {
  for (int code : {1, 2, 3}) {
    b->Args({20, 1, code});
    b->Args({14, 2, code});
  }
}

}  // namespace

// Wall time, and CPU time summed over all threads (BLAS threads included): on a shared machine the
// CPU time is the steadier measure of the work.
BENCHMARK(BM_RawSymbolic)
    ->Apply(sizes)
    ->Apply(orderings)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK(BM_RawNumeric)
    ->Apply(sizes)
    ->Apply(orderings)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK(BM_LuFallback)
    ->Apply(sizes)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK(BM_ShiftFallback)
    ->Apply(sizes)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK(BM_EigenSymbolic)
    ->Apply(sizes)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK(BM_EigenNumeric)
    ->Apply(sizes)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

BENCHMARK_MAIN();
