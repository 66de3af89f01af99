#include "solver/linear_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "solver/blas_threads.hpp"
#include "solver/setting_error.hpp"
#include "solver/umfpack_lu.hpp"

namespace isomuscle::solver {

namespace {

// Adds the wall-clock seconds of its lifetime to a counter.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& seconds)
      : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

std::string to_string(LinearMethod method) {
  switch (method) {
    case LinearMethod::None:
      return "none";
    case LinearMethod::Cholesky:
      return "Cholesky (CHOLMOD)";
    case LinearMethod::Lu:
      return "LU (UMFPACK)";
  }
  return "unknown";
}

std::string to_string(IndefiniteResponse response) {
  switch (response) {
    case IndefiniteResponse::Fail:
      return "fail";
    case IndefiniteResponse::Lu:
      return "lu";
    case IndefiniteResponse::Shift:
      return "shift";
  }
  return "unknown";
}

void LinearSolverSettings::validate() const {
  if (method == LinearMethod::None) {
    throw SettingError("method", "must be Cholesky (CHOLMOD) or LU (UMFPACK) (got none)");
  }
  if (!(shift_initial > 0.0) || !std::isfinite(shift_initial)) {
    throw SettingError("shift_initial",
                       "must be a finite number > 0 (got " + format_number(shift_initial) + ")");
  }
  if (!(shift_growth > 1.0) || !std::isfinite(shift_growth)) {
    throw SettingError("shift_growth",
                       "must be a finite number > 1 (got " + format_number(shift_growth) + ")");
  }
  if (shift_attempts < 1 || shift_attempts > 100) {
    throw SettingError("shift_attempts",
                       "must be in [1, 100] (got " + std::to_string(shift_attempts) + ")");
  }
  if (blas_threads < 0 || blas_threads > 4096) {
    throw SettingError("blas_threads",
                       "must be in [0, 4096] (got " + std::to_string(blas_threads) + ")");
  }
}

struct LinearSolver::Impl {
  LinearSolverSettings settings;
  CholmodCholesky cholesky;
  UmfpackLu lu;
  std::vector<int> outer;  // the analysed pattern
  std::vector<int> inner;
  bool have_pattern = false;
  bool lu_analysed = false;  // for the current pattern
  // Upper storage expanded to both triangles for LU: value k of the upper matrix goes to
  // full.valuePtr()[to_full[2k]] and (off the diagonal) [to_full[2k + 1]].
  SparseMatrix full;
  std::vector<int> to_full;
  LinearMethod active = LinearMethod::None;
  double last_shift = 0.0;  // tau of the last successful shifted factorisation, 0 when none
  FactorizationReport report;
  LinearSolverStatistics stats;

  explicit Impl(const LinearSolverSettings& s) : settings(s), cholesky(s.ordering) {}

  bool same_pattern(const SparseMatrix& a) const {
    return have_pattern && a.rows() + 1 == static_cast<Eigen::Index>(outer.size()) &&
           a.nonZeros() == static_cast<Eigen::Index>(inner.size()) &&
           std::equal(outer.begin(), outer.end(), a.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), a.innerIndexPtr());
  }

  // New pattern: keep a copy, check the triangle, analyse for Cholesky (LU lazily, when needed).
  void analyse(const SparseMatrix& a) {
    const auto n = static_cast<int>(a.rows());
    if (settings.storage == MatrixStorage::Upper) {
      for (int j = 0; j < n; ++j) {
        for (int k = a.outerIndexPtr()[j]; k < a.outerIndexPtr()[j + 1]; ++k) {
          if (a.innerIndexPtr()[k] > j) {
            throw std::invalid_argument(
                "LinearSolver: entry (" + std::to_string(a.innerIndexPtr()[k]) + ", " +
                std::to_string(j) +
                ") lies below the diagonal but the settings say MatrixStorage::Upper; assemble "
                "the upper triangle only (SparsityPattern with Upper) or use Full storage");
          }
        }
      }
    }
    if (have_pattern) {
      ++stats.pattern_changes;
    }
    outer.assign(a.outerIndexPtr(), a.outerIndexPtr() + n + 1);
    inner.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
    have_pattern = true;
    lu_analysed = false;
    active = LinearMethod::None;
    if (settings.method == LinearMethod::Cholesky) {
      ScopedTimer timer(stats.time.symbolic);
      cholesky.analyze(a);
      ++stats.symbolic_analyses;
    }
  }

  // The symmetric expansion K = U + U^T - diag(U) of an upper-stored matrix: pattern and map built
  // once per pattern (columns filled in ascending order keep the rows sorted).
  void build_full_pattern(const SparseMatrix& a) {
    const auto n = static_cast<int>(a.rows());
    const int* ap = a.outerIndexPtr();
    const int* ai = a.innerIndexPtr();
    std::vector<int> count(static_cast<std::size_t>(n) + 1, 0);
    for (int j = 0; j < n; ++j) {
      for (int k = ap[j]; k < ap[j + 1]; ++k) {
        ++count[j + 1];
        if (ai[k] != j) {
          ++count[ai[k] + 1];
        }
      }
    }
    for (int j = 0; j < n; ++j) {
      count[j + 1] += count[j];
    }
    full = SparseMatrix(n, n);
    full.resizeNonZeros(count[n]);
    std::copy(count.begin(), count.end(), full.outerIndexPtr());
    to_full.assign(2 * static_cast<std::size_t>(a.nonZeros()), -1);
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (int j = 0; j < n; ++j) {
      for (int k = ap[j]; k < ap[j + 1]; ++k) {
        const int i = ai[k];
        full.innerIndexPtr()[fill[j]] = i;
        to_full[2 * static_cast<std::size_t>(k)] = fill[j]++;
        if (i != j) {
          full.innerIndexPtr()[fill[i]] = j;
          to_full[2 * static_cast<std::size_t>(k) + 1] = fill[i]++;
        }
      }
    }
  }

  void expand_values(const SparseMatrix& a) {
    double* values = full.valuePtr();
    for (Eigen::Index k = 0; k < a.nonZeros(); ++k) {
      const double v = a.valuePtr()[k];
      values[to_full[2 * k]] = v;
      if (to_full[2 * k + 1] >= 0) {
        values[to_full[2 * k + 1]] = v;
      }
    }
  }

  // LU of a (expanded first with Upper storage); fills report.
  void factorize_lu(const SparseMatrix& a, bool fell_back, const std::string& cholesky_message) {
    const bool expand = settings.storage == MatrixStorage::Upper;
    if (expand) {
      // Filled before the analysis too: UMFPACK's analysis reads the values (given an unfilled
      // copy it saw no diagonal and chose its unsymmetric strategy).
      if (!lu_analysed) {
        build_full_pattern(a);
      }
      expand_values(a);
    }
    const SparseMatrix& matrix = expand ? full : a;
    if (!lu_analysed) {
      ScopedTimer timer(stats.time.symbolic);
      LuAnalysisOptions options;
      if (expand) {
        // An expanded matrix is symmetric: UMFPACK's symmetric strategy and, where Cholesky was
        // analysed, CHOLMOD's fill-reducing order of the same pattern (umfpack_lu.hpp; on two DAO
        // tangents 13-35 % fewer flops than UMFPACK's AMD).
        options.symmetric = true;
        if (cholesky.analyzed()) {
          options.column_order = cholesky.permutation();
        }
      }
      lu.analyze(matrix, options);
      lu_analysed = true;
      ++stats.lu_symbolic_analyses;
    }
    LuStatus status;
    {
      ScopedTimer timer(stats.time.numeric);
      ScopedTimer lu_timer(stats.time.lu);
      status = lu.factorize(matrix);
    }
    ++stats.lu_factorizations;
    if (fell_back) {
      ++stats.lu_fallbacks;
    }
    report.fell_back = fell_back;
    if (!status.ok) {
      report.message = fell_back ? cholesky_message + "; then " + status.message : status.message;
      return;
    }
    report.ok = true;
    report.method = LinearMethod::Lu;
    report.rcond = lu.rcond();
    active = LinearMethod::Lu;
    if (fell_back) {
      report.message = cholesky_message + "; factorised by LU instead";
    }
  }

  // Cholesky of a + beta I, beta = tau mean|a_ii|, for growing tau (the header's Shift); fills
  // report. The mean of the diagonal makes tau dimensionless: the tangent's own stiffness scale.
  void factorize_shifted(const SparseMatrix& a, const std::string& cholesky_message) {
    const double scale = a.diagonal().cwiseAbs().mean();
    report.fell_back = true;
    if (!(scale > 0.0)) {
      report.message = cholesky_message + "; no shift possible (the diagonal is zero)";
      return;
    }
    double tau = std::max(settings.shift_initial, last_shift / settings.shift_growth);
    for (int attempt = 0; attempt < settings.shift_attempts; ++attempt) {
      CholeskyStatus status;
      {
        ScopedTimer timer(stats.time.numeric);
        ScopedTimer shifted_timer(stats.time.shifted);
        status = cholesky.factorize(a, tau * scale);
      }
      ++stats.cholesky_factorizations;
      if (status.ok) {
        ++stats.shifted_factorizations;
        stats.max_shift = std::max(stats.max_shift, tau);
        last_shift = tau;
        report.ok = true;
        report.method = LinearMethod::Cholesky;
        report.shift = tau;
        report.rcond = cholesky.rcond();
        report.message =
            cholesky_message + "; factorised K + " + format_number(tau) + " mean|K_ii| I instead";
        active = LinearMethod::Cholesky;
        return;
      }
      ++stats.failed_shifts;
      if (!status.not_positive_definite) {
        report.message = cholesky_message + "; then, shifted by " + format_number(tau) +
                         " mean|K_ii|: " + status.message;
        return;
      }
      tau *= settings.shift_growth;
    }
    last_shift = 0.0;
    report.message = cholesky_message +
                     "; K + tau mean|K_ii| I was not positive definite either for " +
                     std::to_string(settings.shift_attempts) +
                     " shifts up to tau = " + format_number(tau / settings.shift_growth);
  }
};

LinearSolver::LinearSolver(LinearSolverSettings settings) {
  settings.validate();
  if (settings.blas_threads > 0)
    set_blas_threads(settings.blas_threads);
  impl_ = std::make_unique<Impl>(settings);
}
LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

// Factorisation of K for K du = -r: Cholesky K = P^T L L^T P, else LU (see header).
FactorizationReport LinearSolver::factorize(const SparseMatrix& a) {
  Impl& s = *impl_;
  if (a.rows() != a.cols() || !a.isCompressed() || a.rows() == 0) {
    throw std::invalid_argument(
        "LinearSolver::factorize: the matrix must be square, non-empty and compressed (got " +
        std::to_string(a.rows()) + " x " + std::to_string(a.cols()) +
        (a.isCompressed() ? ")" : ", not compressed: call makeCompressed())"));
  }
  if (!s.same_pattern(a)) {
    s.analyse(a);
  }
  s.report = FactorizationReport{};
  s.active = LinearMethod::None;
  for (int j = 0; j < a.cols(); ++j) {
    for (int k = a.outerIndexPtr()[j]; k < a.outerIndexPtr()[j + 1]; ++k) {
      if (!std::isfinite(a.valuePtr()[k])) {
        s.report.message = "the matrix has a non-finite entry " + format_number(a.valuePtr()[k]) +
                           " at (" + std::to_string(a.innerIndexPtr()[k]) + ", " +
                           std::to_string(j) + ")";
        ++s.stats.failures;
        return s.report;
      }
    }
  }
  if (s.settings.method == LinearMethod::Cholesky) {
    CholeskyStatus status;
    {
      ScopedTimer timer(s.stats.time.numeric);
      status = s.cholesky.factorize(a);
    }
    ++s.stats.cholesky_factorizations;
    if (status.ok) {
      s.report.ok = true;
      s.report.method = LinearMethod::Cholesky;
      s.report.rcond = s.cholesky.rcond();
      s.active = LinearMethod::Cholesky;
      s.last_shift = 0.0;
      return s.report;
    }
    ++s.stats.cholesky_failures;
    // LU takes any failed matrix (as it always did); a shift only helps an indefinite one.
    const bool shift = s.settings.indefinite == IndefiniteResponse::Shift;
    if (s.settings.indefinite == IndefiniteResponse::Fail ||
        (shift && !status.not_positive_definite)) {
      s.report.message =
          status.message +
          (s.settings.indefinite == IndefiniteResponse::Fail
               ? " (response to an indefinite tangent: fail, no LU or shifted factorisation tried)"
               : "");
      ++s.stats.failures;
      return s.report;
    }
    if (shift) {
      s.factorize_shifted(a, status.message);
    } else {
      s.factorize_lu(a, true, status.message);
    }
  } else {
    s.factorize_lu(a, false, "");
  }
  if (!s.report.ok) {
    ++s.stats.failures;
  }
  return s.report;
}

// du = K^{-1} b by the active factorisation's triangular solves.
void LinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& s = *impl_;
  ScopedTimer timer(s.stats.time.solve);
  switch (s.active) {
    case LinearMethod::Cholesky:
      s.cholesky.solve(b, x);
      break;
    case LinearMethod::Lu:
      s.lu.solve(b, x);
      break;
    case LinearMethod::None:
      throw std::logic_error(
          "LinearSolver::solve called without a successful factorisation (last: " +
          (s.report.message.empty() ? std::string("none") : s.report.message) + ")");
  }
  ++s.stats.solves;
}

void LinearSolver::release_factorization() {
  Impl& s = *impl_;
  s.cholesky.release_numeric();
  s.lu.release_numeric();
  s.active = LinearMethod::None;
}

const FactorizationReport& LinearSolver::last_report() const {
  return impl_->report;
}
const LinearSolverStatistics& LinearSolver::statistics() const {
  return impl_->stats;
}
const LinearSolverSettings& LinearSolver::settings() const {
  return impl_->settings;
}
const CholmodCholesky& LinearSolver::cholesky() const {
  return impl_->cholesky;
}
const UmfpackLu& LinearSolver::lu() const {
  return impl_->lu;
}

}  // namespace isomuscle::solver
