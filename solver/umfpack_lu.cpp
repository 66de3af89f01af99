#include "solver/umfpack_lu.hpp"

#include <umfpack.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace isomuscle::solver {

namespace {

std::string status_text(int status) {
  switch (status) {
    case UMFPACK_OK:
      return "ok";
    case UMFPACK_WARNING_singular_matrix:
      return "matrix singular (zero pivot)";
    case UMFPACK_WARNING_determinant_underflow:
      return "determinant underflow";
    case UMFPACK_WARNING_determinant_overflow:
      return "determinant overflow";
    case UMFPACK_ERROR_out_of_memory:
      return "out of memory";
    case UMFPACK_ERROR_invalid_matrix:
      return "invalid matrix (unsorted or duplicate row indices)";
    case UMFPACK_ERROR_different_pattern:
      return "pattern differs from the analysed one";
    default:
      return "status " + std::to_string(status);
  }
}

// The 64-bit index version of UMFPACK (umfpack_dl_*): the 32-bit one (umfpack_di_*) addresses its
// numeric object in int-sized units and answers "out of memory" once the estimate passes 2^31
// units, whatever memory the machine has. Seen at 152k unknowns (the DAO on 0.6 mm 10-node
// tetrahedra: an indefinite tangent whose LU fallback failed, so the step was cut), and on a
// 3 x 30^3 pattern of 27-point 3D couplings: umfpack_di estimated 1.8e9 units and failed,
// umfpack_dl factorised it in 4 GB.
using Index = SuiteSparse_long;

// The column pointers and row indices of a as UMFPACK's 64-bit indices.
void copy_pattern(const SparseMatrix& a, std::vector<Index>& columns, std::vector<Index>& rows) {
  columns.assign(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1);
  rows.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
}

void check_matrix(const SparseMatrix& a, const char* where) {
  if (a.rows() != a.cols() || !a.isCompressed()) {
    throw std::invalid_argument(std::string("UmfpackLu::") + where +
                                ": the matrix must be square and compressed (got " +
                                std::to_string(a.rows()) + " x " + std::to_string(a.cols()) + ")");
  }
}

}  // namespace

struct UmfpackLu::Impl {
  void* symbolic = nullptr;
  void* numeric = nullptr;
  Index n = -1;
  double rcond = 0.0;
  bool symmetric_strategy = false;
  double factor_nonzeros = 0.0;
  // The factorised matrix, for iterative refinement in solve: its values, and its pattern in
  // 64-bit indices.
  SparseMatrix matrix;
  std::vector<Index> columns, rows;
  std::vector<double> control = std::vector<double>(UMFPACK_CONTROL);
  std::vector<double> info = std::vector<double>(UMFPACK_INFO);
  std::vector<Index> wi;  // umfpack_dl_wsolve workspace, reused
  std::vector<double> w;

  Impl() { umfpack_dl_defaults(control.data()); }
  ~Impl() {
    umfpack_dl_free_numeric(&numeric);
    umfpack_dl_free_symbolic(&symbolic);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
};

UmfpackLu::UmfpackLu() : impl_(std::make_unique<Impl>()) {}
UmfpackLu::~UmfpackLu() = default;
UmfpackLu::UmfpackLu(UmfpackLu&&) noexcept = default;
UmfpackLu& UmfpackLu::operator=(UmfpackLu&&) noexcept = default;

// Symbolic analysis: column pre-ordering Q and frontal matrix structure (umfpack_dl_symbolic, or
// umfpack_dl_qsymbolic with a given order).
void UmfpackLu::analyze(const SparseMatrix& a, const LuAnalysisOptions& options) {
  check_matrix(a, "analyze");
  Impl& s = *impl_;
  umfpack_dl_free_numeric(&s.numeric);
  umfpack_dl_free_symbolic(&s.symbolic);
  const Index n = a.rows();
  std::vector<Index> order;
  if (!options.column_order.empty()) {
    std::vector<bool> seen(static_cast<std::size_t>(n), false);
    bool permutation = options.column_order.size() == static_cast<std::size_t>(n);
    for (std::size_t k = 0; permutation && k < options.column_order.size(); ++k) {
      const int j = options.column_order[k];
      permutation = j >= 0 && j < n && !seen[static_cast<std::size_t>(j)];
      if (permutation) {
        seen[static_cast<std::size_t>(j)] = true;
      }
    }
    if (!permutation) {
      throw std::invalid_argument("UmfpackLu::analyze: the column order (" +
                                  std::to_string(options.column_order.size()) +
                                  " entries) is not a permutation of 0.." + std::to_string(n - 1));
    }
    order.assign(options.column_order.begin(), options.column_order.end());
  }
  copy_pattern(a, s.columns, s.rows);
  umfpack_dl_defaults(s.control.data());
  if (options.symmetric) {
    s.control[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_SYMMETRIC;
  }
  const int status = static_cast<int>(
      order.empty()
          ? umfpack_dl_symbolic(n, n, s.columns.data(), s.rows.data(), a.valuePtr(), &s.symbolic,
                                s.control.data(), s.info.data())
          : umfpack_dl_qsymbolic(n, n, s.columns.data(), s.rows.data(), a.valuePtr(), order.data(),
                                 &s.symbolic, s.control.data(), s.info.data()));
  if (status != UMFPACK_OK) {
    umfpack_dl_free_symbolic(&s.symbolic);
    throw std::runtime_error("UMFPACK symbolic analysis of a " + std::to_string(n) + " x " +
                             std::to_string(n) + " matrix failed: " + status_text(status));
  }
  s.symmetric_strategy = s.info[UMFPACK_STRATEGY_USED] == UMFPACK_STRATEGY_SYMMETRIC;
  s.n = n;
}

// Numeric factorisation P R^{-1} A Q = L U with row scaling R (umfpack_dl_numeric).
LuStatus UmfpackLu::factorize(const SparseMatrix& a) {
  check_matrix(a, "factorize");
  Impl& s = *impl_;
  if (s.symbolic == nullptr) {
    throw std::logic_error("UmfpackLu::factorize called before analyze");
  }
  if (a.rows() != s.n) {
    throw std::invalid_argument("UmfpackLu::factorize: matrix has " + std::to_string(a.rows()) +
                                " rows but the analysis was for " + std::to_string(s.n));
  }
  umfpack_dl_free_numeric(&s.numeric);
  copy_pattern(a, s.columns, s.rows);
  const int status =
      static_cast<int>(umfpack_dl_numeric(s.columns.data(), s.rows.data(), a.valuePtr(), s.symbolic,
                                          &s.numeric, s.control.data(), s.info.data()));
  LuStatus result;
  s.rcond = s.info[UMFPACK_RCOND];
  if (status == UMFPACK_WARNING_singular_matrix) {
    umfpack_dl_free_numeric(&s.numeric);
    result.singular = true;
    char rcond[32];
    std::snprintf(rcond, sizeof(rcond), "%.3e", s.rcond);
    result.message =
        std::string("LU factorisation found the matrix singular (a zero pivot; rcond estimate ") +
        rcond + ")";
    return result;
  }
  if (status != UMFPACK_OK) {
    umfpack_dl_free_numeric(&s.numeric);
    result.message = "LU factorisation failed: UMFPACK " + status_text(status);
    return result;
  }
  s.matrix = a;
  s.factor_nonzeros = s.info[UMFPACK_LNZ] + s.info[UMFPACK_UNZ];
  result.ok = true;
  return result;
}

// x = A^{-1} b = Q U^{-1} L^{-1} P R^{-1} b (umfpack_dl_wsolve, reused workspace), followed by
// UMFPACK's default of up to two steps of iterative refinement with the factorised matrix.
void UmfpackLu::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& s = *impl_;
  if (s.numeric == nullptr) {
    throw std::logic_error("UmfpackLu::solve called without a successful factorisation");
  }
  if (b.size() != s.n) {
    throw std::invalid_argument("UmfpackLu::solve: right-hand side has size " +
                                std::to_string(b.size()) + ", the matrix " + std::to_string(s.n));
  }
  x.resize(s.n);
  s.wi.resize(static_cast<std::size_t>(s.n));
  s.w.resize(5 * static_cast<std::size_t>(s.n));
  const int status = static_cast<int>(umfpack_dl_wsolve(
      UMFPACK_A, s.columns.data(), s.rows.data(), s.matrix.valuePtr(), x.data(), b.data(),
      s.numeric, s.control.data(), s.info.data(), s.wi.data(), s.w.data()));
  if (status != UMFPACK_OK) {
    throw std::runtime_error("UMFPACK solve failed: " + status_text(status));
  }
}

void UmfpackLu::release_numeric() {
  umfpack_dl_free_numeric(&impl_->numeric);
}

bool UmfpackLu::analyzed() const {
  return impl_->symbolic != nullptr;
}
bool UmfpackLu::factorized() const {
  return impl_->numeric != nullptr;
}
double UmfpackLu::rcond() const {
  return impl_->rcond;
}
bool UmfpackLu::symmetric_strategy() const {
  return impl_->symmetric_strategy;
}
double UmfpackLu::factor_nonzeros() const {
  return impl_->factor_nonzeros;
}

}  // namespace isomuscle::solver
