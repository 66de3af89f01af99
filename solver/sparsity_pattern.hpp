#pragma once
// The compressed-sparse-column (CSC) pattern of the free x free tangent, built once from the
// elements' DOF lists, and the scatter map that assembles an element matrix without any search:
//
//   K = sum_e  P_e^T K_e P_e          (standard finite-element assembly)
//   values[pos_e[k]] += K_e.data()[k]  for k = a + b n_e (column-major local index)
//
// pos_e[k] is the position of entry (dofs_e[a], dofs_e[b]) in the CSC value array, or -1 when the
// entry is not stored (a prescribed DOF, or below the diagonal with MatrixStorage::Upper). With
// Upper storage each stored global entry K_ij (i <= j) receives every local pair that maps to it,
// so repeated DOFs in one element (merged coincident control points) sum correctly.
//
// The stored map costs 4 n_e^2 bytes per element (IGA p = 2 hexahedral elements, n_e = 81: 26 KB;
// linear tetrahedra, n_e = 12: 576 B). ScatterMode::Search stores nothing and finds each position
// by binary search in its column instead (same values, bitwise: the additions happen in the same
// order); use it when memory_bytes() of the stored map is too much.
#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

#include "solver/element_dofs.hpp"
#include "solver/matrix_storage.hpp"
#include "solver/nonlinear_problem.hpp"

namespace isomuscle::solver {

enum class ScatterMode { Stored, Search };

class SparsityPattern {
 public:
  SparsityPattern() = default;
  // Builds the pattern of the n_free x n_free matrix. Throws std::invalid_argument when a DOF index
  // is >= n_free (naming the element) or a free DOF belongs to no element (its row and column
  // would be empty and the matrix singular).
  SparsityPattern(ElementDofs elements, int n_free, MatrixStorage storage = MatrixStorage::Upper,
                  ScatterMode mode = ScatterMode::Stored);

  int size() const { return n_; }
  int non_zeros() const { return static_cast<int>(inner_.size()); }
  MatrixStorage storage() const { return storage_; }
  ScatterMode scatter_mode() const { return mode_; }
  const ElementDofs& elements() const { return elements_; }

  // A compressed n x n matrix with this pattern and all values zero.
  SparseMatrix make_matrix() const;
  // True when matrix is compressed and has exactly this pattern (O(nnz) comparison).
  bool matches(const SparseMatrix& matrix) const;

  // Positions of element's entries in the value array, column-major local order, -1 where not
  // stored. ScatterMode::Stored only (throws std::logic_error otherwise).
  std::span<const int> scatter(int element) const;

  // values[pos] += ke(a, b) for every stored entry (the assembly sum above). values is the value
  // array of a matrix with this pattern (make_matrix().valuePtr()); ke is n_e x n_e, column-major.
  // Throws std::invalid_argument when ke has the wrong size.
  void add_element_matrix(int element, const Eigen::Ref<const Eigen::MatrixXd>& ke,
                          double* values) const;
  // Same, checking that matrix has this pattern's size and number of entries.
  void add_element_matrix(int element, const Eigen::Ref<const Eigen::MatrixXd>& ke,
                          SparseMatrix& matrix) const;
  // r[dofs_e[a]] += fe[a] for every free local DOF a (f = sum_e P_e^T f_e).
  void add_element_vector(int element, const Eigen::Ref<const Eigen::VectorXd>& fe,
                          Eigen::VectorXd& r) const;

  // Bytes held by the pattern (column starts, row indices) and by the scatter map.
  std::size_t pattern_memory_bytes() const;
  std::size_t scatter_memory_bytes() const;

 private:
  int find_position(int row, int col) const;

  ElementDofs elements_;
  int n_ = 0;
  MatrixStorage storage_ = MatrixStorage::Upper;
  ScatterMode mode_ = ScatterMode::Stored;
  std::vector<int> outer_;                    // column starts, n + 1
  std::vector<int> inner_;                    // row indices, sorted within each column
  std::vector<std::size_t> scatter_offsets_;  // element -> start in scatter_
  std::vector<int> scatter_;
};

}  // namespace isomuscle::solver
