#include "solver/element_colouring.hpp"

#include <omp.h>

#include <exception>
#include <limits>
#include <stdexcept>
#include <string>

namespace isomuscle::solver {

// Greedy distance-1 colouring of the element graph (elements adjacent when they share a DOF).
ElementColouring::ElementColouring(const ElementDofs& elements) {
  const int n_elements = elements.n_elements();
  const int n_dofs = elements.index_bound();
  // DOF -> elements (CSR).
  std::vector<int> start(static_cast<std::size_t>(n_dofs) + 1, 0);
  for (int e = 0; e < n_elements; ++e) {
    for (int dof : elements.dofs(e)) {
      if (dof >= 0) {
        ++start[dof + 1];
      }
    }
  }
  for (int i = 0; i < n_dofs; ++i) {
    start[i + 1] += start[i];
  }
  std::vector<int> adjacency(static_cast<std::size_t>(start[n_dofs]));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int e = 0; e < n_elements; ++e) {
      for (int dof : elements.dofs(e)) {
        if (dof >= 0) {
          adjacency[fill[dof]++] = e;
        }
      }
    }
  }

  colour_of_.assign(static_cast<std::size_t>(n_elements), -1);
  std::vector<int> forbidden;  // forbidden[c] == e: colour c is taken by a neighbour of e
  std::vector<int> colour_size;
  for (int e = 0; e < n_elements; ++e) {
    for (int dof : elements.dofs(e)) {
      if (dof < 0) {
        continue;
      }
      for (int k = start[dof]; k < start[dof + 1]; ++k) {
        const int c = colour_of_[adjacency[k]];
        if (c >= 0) {
          forbidden[c] = e;
        }
      }
    }
    int colour = 0;
    while (colour < static_cast<int>(forbidden.size()) && forbidden[colour] == e) {
      ++colour;
    }
    if (colour == static_cast<int>(forbidden.size())) {
      forbidden.push_back(-1);
      colour_size.push_back(0);
    }
    colour_of_[e] = colour;
    ++colour_size[colour];
  }

  const int n_colours = static_cast<int>(colour_size.size());
  colour_start_.assign(static_cast<std::size_t>(n_colours) + 1, 0);
  for (int c = 0; c < n_colours; ++c) {
    colour_start_[c + 1] = colour_start_[c] + colour_size[c];
  }
  members_.resize(static_cast<std::size_t>(n_elements));
  std::vector<int> fill(colour_start_.begin(), colour_start_.end() - 1);
  for (int e = 0; e < n_elements; ++e) {
    members_[fill[colour_of_[e]]++] = e;
  }
}

int resolve_thread_count(int threads) {
  if (threads < 0) {
    throw std::invalid_argument("'threads' must be >= 0 (0: OpenMP default) (got " +
                                std::to_string(threads) + ")");
  }
  return threads > 0 ? threads : omp_get_max_threads();
}

// Coloured element loop (see header); no equation, the body computes the element terms.
EvaluationStatus for_each_element_coloured(
    const ElementColouring& colouring, int threads,
    const std::function<EvaluationStatus(int element, int thread)>& body) {
  const int n_threads = resolve_thread_count(threads);
  constexpr int kNone = std::numeric_limits<int>::max();
  for (int colour = 0; colour < colouring.n_colours(); ++colour) {
    const std::span<const int> members = colouring.elements(colour);
    const int n_members = static_cast<int>(members.size());
    int first_failed = kNone;  // lowest element index that failed or threw
    EvaluationStatus failure;
    std::exception_ptr error;
#pragma omp parallel for num_threads(n_threads) schedule(dynamic, 4)
    for (int k = 0; k < n_members; ++k) {
      const int element = members[k];
      EvaluationStatus status;
      std::exception_ptr thrown;
      try {
        status = body(element, omp_get_thread_num());
      } catch (...) {
        thrown = std::current_exception();
      }
      if (!status.ok || thrown) {
#pragma omp critical(isomuscle_solver_colour_failure)
        {
          if (element < first_failed) {
            first_failed = element;
            failure = std::move(status);
            error = thrown;
          }
        }
      }
    }
    if (error) {
      std::rethrow_exception(error);
    }
    if (first_failed != kNone) {
      return failure;
    }
  }
  return EvaluationStatus::success();
}

}  // namespace isomuscle::solver
