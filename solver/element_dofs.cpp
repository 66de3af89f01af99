#include "solver/element_dofs.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace isomuscle::solver {

ElementDofs::ElementDofs(const std::vector<std::vector<int>>& lists) {
  std::size_t total = 0;
  for (const auto& list : lists) {
    total += list.size();
  }
  offsets_.reserve(lists.size() + 1);
  dofs_.reserve(total);
  for (const auto& list : lists) {
    add_element(list);
  }
}

// Appends one element's DOF list (no equation: bookkeeping). Indices are dimensionless.
int ElementDofs::add_element(std::span<const int> dofs) {
  const int element = n_elements();
  if (dofs_.size() + dofs.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw std::invalid_argument("ElementDofs: more than 2^31 - 1 element DOF entries in total");
  }
  for (std::size_t a = 0; a < dofs.size(); ++a) {
    if (dofs[a] < kPrescribed) {
      throw std::invalid_argument("ElementDofs: element " + std::to_string(element) +
                                  ", local DOF " + std::to_string(a) + " has index " +
                                  std::to_string(dofs[a]) +
                                  "; valid are a free-DOF index >= 0 or -1 (prescribed)");
    }
    index_bound_ = std::max(index_bound_, dofs[a] + 1);
  }
  dofs_.insert(dofs_.end(), dofs.begin(), dofs.end());
  offsets_.push_back(static_cast<int>(dofs_.size()));
  max_size_ = std::max(max_size_, static_cast<int>(dofs.size()));
  return element;
}

}  // namespace isomuscle::solver
