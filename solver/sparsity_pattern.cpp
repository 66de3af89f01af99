#include "solver/sparsity_pattern.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace isomuscle::solver {

namespace {

// Whether local pair (row, col) of global free indices is stored.
bool is_stored(int row, int col, MatrixStorage storage) {
  return row >= 0 && col >= 0 && (storage == MatrixStorage::Full || row <= col);
}

}  // namespace

// Pattern of K = sum_e P_e^T K_e P_e: entry (i, j) exists when some element holds both i and j.
// Built column by column from the DOF -> element adjacency with a marker array, O(sum_e n_e^2).
SparsityPattern::SparsityPattern(ElementDofs elements, int n_free, MatrixStorage storage,
                                 ScatterMode mode)
    : elements_(std::move(elements)), n_(n_free), storage_(storage), mode_(mode) {
  if (n_free < 0) {
    throw std::invalid_argument("SparsityPattern: n_free must be >= 0 (got " +
                                std::to_string(n_free) + ")");
  }
  const int n_elements = elements_.n_elements();
  // DOF -> elements adjacency (CSR), elements ascending.
  std::vector<int> adjacency_start(static_cast<std::size_t>(n_) + 1, 0);
  for (int e = 0; e < n_elements; ++e) {
    for (int dof : elements_.dofs(e)) {
      if (dof >= n_) {
        throw std::invalid_argument("SparsityPattern: element " + std::to_string(e) +
                                    " holds DOF " + std::to_string(dof) + " but n_free is " +
                                    std::to_string(n_) + " (valid: 0 ... n_free - 1, or -1)");
      }
      if (dof >= 0) {
        ++adjacency_start[dof + 1];
      }
    }
  }
  for (int i = 0; i < n_; ++i) {
    if (adjacency_start[i + 1] == 0) {
      throw std::invalid_argument("SparsityPattern: free DOF " + std::to_string(i) +
                                  " belongs to no element, so its row and column would be empty "
                                  "(a singular matrix); number only DOFs that elements use");
    }
    adjacency_start[i + 1] += adjacency_start[i];
  }
  std::vector<int> adjacency(static_cast<std::size_t>(adjacency_start[n_]));
  {
    std::vector<int> fill(adjacency_start.begin(), adjacency_start.end() - 1);
    for (int e = 0; e < n_elements; ++e) {
      for (int dof : elements_.dofs(e)) {
        // An element listing a DOF twice is entered once.
        if (dof >= 0 && (fill[dof] == adjacency_start[dof] || adjacency[fill[dof] - 1] != e)) {
          adjacency[fill[dof]++] = e;
        }
      }
    }
    for (int i = 0; i < n_; ++i) {
      // Shorten the unused tail left by repeated DOFs: mark it with -1 and skip below.
      std::fill(adjacency.begin() + fill[i], adjacency.begin() + adjacency_start[i + 1], -1);
    }
  }

  // Columns: rows i of every element holding column j, sorted, unique (marker = last column).
  outer_.assign(static_cast<std::size_t>(n_) + 1, 0);
  std::vector<int> marker(static_cast<std::size_t>(n_), -1);
  std::vector<int> column;
  for (int j = 0; j < n_; ++j) {
    column.clear();
    for (int k = adjacency_start[j]; k < adjacency_start[j + 1]; ++k) {
      const int e = adjacency[k];
      if (e < 0) {
        break;
      }
      for (int i : elements_.dofs(e)) {
        if (is_stored(i, j, storage_) && marker[i] != j) {
          marker[i] = j;
          column.push_back(i);
        }
      }
    }
    std::sort(column.begin(), column.end());
    inner_.insert(inner_.end(), column.begin(), column.end());
    outer_[j + 1] = static_cast<int>(inner_.size());
  }

  if (mode_ == ScatterMode::Stored) {
    scatter_offsets_.assign(static_cast<std::size_t>(n_elements) + 1, 0);
    for (int e = 0; e < n_elements; ++e) {
      const auto n_e = static_cast<std::size_t>(elements_.size(e));
      scatter_offsets_[e + 1] = scatter_offsets_[e] + n_e * n_e;
    }
    scatter_.resize(scatter_offsets_.back());
    for (int e = 0; e < n_elements; ++e) {
      const std::span<const int> dofs = elements_.dofs(e);
      const std::size_t n_e = dofs.size();
      int* pos = scatter_.data() + scatter_offsets_[e];
      for (std::size_t b = 0; b < n_e; ++b) {
        for (std::size_t a = 0; a < n_e; ++a) {
          pos[a + b * n_e] = find_position(dofs[a], dofs[b]);
        }
      }
    }
  }
}

// Position of (row, col) in the value array by binary search in column col; -1 when not stored.
int SparsityPattern::find_position(int row, int col) const {
  if (!is_stored(row, col, storage_)) {
    return -1;
  }
  const auto begin = inner_.begin() + outer_[col];
  const auto end = inner_.begin() + outer_[col + 1];
  const auto it = std::lower_bound(begin, end, row);
  // Every stored pair of an element is in the pattern by construction.
  return static_cast<int>(it - inner_.begin());
}

SparseMatrix SparsityPattern::make_matrix() const {
  SparseMatrix matrix(n_, n_);
  matrix.resizeNonZeros(static_cast<Eigen::Index>(inner_.size()));
  std::copy(outer_.begin(), outer_.end(), matrix.outerIndexPtr());
  std::copy(inner_.begin(), inner_.end(), matrix.innerIndexPtr());
  std::fill(matrix.valuePtr(), matrix.valuePtr() + inner_.size(), 0.0);
  return matrix;
}

bool SparsityPattern::matches(const SparseMatrix& matrix) const {
  return matrix.isCompressed() && matrix.rows() == n_ && matrix.cols() == n_ &&
         matrix.nonZeros() == static_cast<Eigen::Index>(inner_.size()) &&
         std::equal(outer_.begin(), outer_.end(), matrix.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), matrix.innerIndexPtr());
}

std::span<const int> SparsityPattern::scatter(int element) const {
  if (mode_ != ScatterMode::Stored) {
    throw std::logic_error("SparsityPattern::scatter: built with ScatterMode::Search, no map kept");
  }
  return {scatter_.data() + scatter_offsets_[element],
          scatter_offsets_[element + 1] - scatter_offsets_[element]};
}

// K += P_e^T K_e P_e (restricted to the stored triangle); units those of K_e.
void SparsityPattern::add_element_matrix(int element, const Eigen::Ref<const Eigen::MatrixXd>& ke,
                                         double* values) const {
  const int n_e = elements_.size(element);
  if (ke.rows() != n_e || ke.cols() != n_e) {
    throw std::invalid_argument("SparsityPattern::add_element_matrix: element " +
                                std::to_string(element) + " has " + std::to_string(n_e) +
                                " DOFs but its matrix is " + std::to_string(ke.rows()) + " x " +
                                std::to_string(ke.cols()));
  }
  const Eigen::Index stride = ke.outerStride();
  if (mode_ == ScatterMode::Stored) {
    const int* pos = scatter_.data() + scatter_offsets_[element];
    for (int b = 0; b < n_e; ++b) {
      const double* column = ke.data() + b * stride;
      const int* column_pos = pos + static_cast<std::ptrdiff_t>(b) * n_e;
      for (int a = 0; a < n_e; ++a) {
        if (column_pos[a] >= 0) {
          values[column_pos[a]] += column[a];
        }
      }
    }
    return;
  }
  const std::span<const int> dofs = elements_.dofs(element);
  for (int b = 0; b < n_e; ++b) {
    const double* column = ke.data() + b * stride;
    for (int a = 0; a < n_e; ++a) {
      const int p = find_position(dofs[a], dofs[b]);
      if (p >= 0) {
        values[p] += column[a];
      }
    }
  }
}

void SparsityPattern::add_element_matrix(int element, const Eigen::Ref<const Eigen::MatrixXd>& ke,
                                         SparseMatrix& matrix) const {
  if (!matrix.isCompressed() || matrix.rows() != n_ || matrix.cols() != n_ ||
      matrix.nonZeros() != static_cast<Eigen::Index>(inner_.size())) {
    throw std::invalid_argument(
        "SparsityPattern::add_element_matrix: the matrix is not one made by make_matrix() (size " +
        std::to_string(matrix.rows()) + " x " + std::to_string(matrix.cols()) + ", " +
        std::to_string(matrix.nonZeros()) + " entries; expected " + std::to_string(n_) + " x " +
        std::to_string(n_) + ", " + std::to_string(inner_.size()) + ")");
  }
  add_element_matrix(element, ke, matrix.valuePtr());
}

// f += P_e^T f_e; units those of f_e.
void SparsityPattern::add_element_vector(int element, const Eigen::Ref<const Eigen::VectorXd>& fe,
                                         Eigen::VectorXd& r) const {
  const std::span<const int> dofs = elements_.dofs(element);
  if (fe.size() != static_cast<Eigen::Index>(dofs.size()) || r.size() != n_) {
    throw std::invalid_argument("SparsityPattern::add_element_vector: element " +
                                std::to_string(element) + " has " + std::to_string(dofs.size()) +
                                " DOFs and the pattern " + std::to_string(n_) +
                                " unknowns, but the vectors have sizes " +
                                std::to_string(fe.size()) + " and " + std::to_string(r.size()));
  }
  for (std::size_t a = 0; a < dofs.size(); ++a) {
    if (dofs[a] >= 0) {
      r[dofs[a]] += fe[static_cast<Eigen::Index>(a)];
    }
  }
}

std::size_t SparsityPattern::pattern_memory_bytes() const {
  return (outer_.size() + inner_.size()) * sizeof(int);
}

std::size_t SparsityPattern::scatter_memory_bytes() const {
  return scatter_.size() * sizeof(int) + scatter_offsets_.size() * sizeof(std::size_t);
}

}  // namespace isomuscle::solver
