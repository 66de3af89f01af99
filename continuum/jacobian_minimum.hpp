#pragma once
// The smallest J = det F over the quadrature points of one assembly pass, and where it is: the
// measure of how close a converged state comes to inverting an element (issue #7's robustness
// matrix records it per run; a large stretch or a strong contraction drives it towards 0). Kept
// per assembly thread and combined afterwards, so it costs one comparison per point and no
// extra pass. Shared by iga::Problem and tet::TetProblem.
#include <limits>
#include <span>

namespace isomuscle::continuum {

struct JacobianMinimum {
  double value = std::numeric_limits<double>::infinity();  // +inf before any point was seen
  int element = -1;
  int point = -1;  // local quadrature point

  bool found() const { return element >= 0; }
  // Takes the per-point J of element e (a kernel's ElementWorkspace::J, first nqp entries).
  void take_element(int e, std::span<const double> J);
  // Takes another minimum. Equal values keep the smaller (element, point), so the result does not
  // depend on how elements were spread over threads.
  void take(const JacobianMinimum& other);
  // The minimum of several (e.g. one per assembly thread).
  static JacobianMinimum of(std::span<const JacobianMinimum> parts);
};

}  // namespace isomuscle::continuum
