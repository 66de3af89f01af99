#pragma once
// Deterministic parallel assembly by element colouring: no two elements of one colour share a DOF,
// so the elements of a colour may scatter into the global matrix and vector concurrently without
// locks, each global entry receiving at most one contribution per colour. Colours are processed one
// after another in a fixed order, so every entry is summed in the same order whatever the number
// of threads: 1, 2 or 16 threads give bitwise equal results.
//
// Greedy colouring (elements in index order, each taking the smallest colour free among its
// neighbours); for structured hexahedral meshes of degree p this gives about (p + 1)^3 colours.
#include <functional>
#include <span>
#include <vector>

#include "solver/element_dofs.hpp"
#include "solver/nonlinear_problem.hpp"

namespace isomuscle::solver {

class ElementColouring {
 public:
  ElementColouring() = default;
  // Colours the elements so that two elements sharing a DOF index >= 0 differ in colour. Pass the
  // DOF lists that the scatter writes to (free DOFs; or all DOFs when reactions at prescribed DOFs
  // are assembled too).
  explicit ElementColouring(const ElementDofs& elements);

  int n_colours() const { return static_cast<int>(colour_start_.size()) - 1; }
  int n_elements() const { return static_cast<int>(colour_of_.size()); }
  // Elements of one colour, ascending.
  std::span<const int> elements(int colour) const {
    return {members_.data() + colour_start_[colour],
            static_cast<std::size_t>(colour_start_[colour + 1] - colour_start_[colour])};
  }
  int colour_of(int element) const { return colour_of_[element]; }

 private:
  std::vector<int> colour_of_;
  std::vector<int> colour_start_{0};
  std::vector<int> members_;
};

// The number of threads that `threads` means: threads itself when > 0, else OpenMP's default
// (omp_get_max_threads()). Size per-thread workspaces with it.
int resolve_thread_count(int threads);

// Calls body(element, thread) for every element: colour after colour, the elements of one colour
// concurrently on resolve_thread_count(threads) threads (thread in 0 ... count - 1 names the
// caller's per-thread workspace). body returns a failure status to stop the assembly: the colour
// under way is finished, later colours are skipped, and the failure of the lowest-numbered failed
// element is returned (deterministic). An exception thrown by body is rethrown on the calling
// thread (the one from the lowest-numbered element).
EvaluationStatus for_each_element_coloured(
    const ElementColouring& colouring, int threads,
    const std::function<EvaluationStatus(int element, int thread)>& body);

}  // namespace isomuscle::solver
