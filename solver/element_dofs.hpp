#pragma once
// The degrees of freedom of every element, flattened (CSR-like): element e owns the global indices
// dofs[offsets[e]] ... dofs[offsets[e + 1] - 1] in its local order (the order of the rows and
// columns of its element matrix). A free DOF has its index in the free numbering 0 ... n - 1; a
// prescribed (Dirichlet) DOF is kPrescribed and is skipped by assembly. A DOF may occur twice in
// one element (coincident control points merged into one DOF, e.g. a collapsed centreline row): its
// contributions are summed.
#include <span>
#include <vector>

namespace isomuscle::solver {

inline constexpr int kPrescribed = -1;

class ElementDofs {
 public:
  ElementDofs() = default;
  // One list per element. Throws std::invalid_argument naming the element and local index when an
  // entry is < -1.
  explicit ElementDofs(const std::vector<std::vector<int>>& lists);

  // Appends one element; returns its index. Throws std::invalid_argument for entries < -1.
  int add_element(std::span<const int> dofs);

  int n_elements() const { return static_cast<int>(offsets_.size()) - 1; }
  std::span<const int> dofs(int element) const {
    return {dofs_.data() + offsets_[element],
            static_cast<std::size_t>(offsets_[element + 1] - offsets_[element])};
  }
  int size(int element) const { return offsets_[element + 1] - offsets_[element]; }
  // Offset of element's first entry in the flattened list (the scatter map uses the squares).
  int offset(int element) const { return offsets_[element]; }
  // Largest number of DOFs of one element (0 when there are no elements).
  int max_element_size() const { return max_size_; }
  // Largest DOF index + 1 (0 when every DOF is prescribed).
  int index_bound() const { return index_bound_; }

 private:
  std::vector<int> offsets_{0};
  std::vector<int> dofs_;
  int max_size_ = 0;
  int index_bound_ = 0;
};

}  // namespace isomuscle::solver
