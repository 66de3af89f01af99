#pragma once
// The smallest and the largest J = det F over the quadrature points of one assembly pass, and
// where they are. The smallest measures how close a converged state comes to inverting an element
// (issue #7's robustness matrix records it per run; a large stretch or a strong contraction drives
// it towards 0). The range [smallest, largest] is the pointwise volume change: the mixed
// formulation holds only each element's mean J~ to the law (J~ - 1 ~ p~ / kappa), and leaves J free
// inside the element, so the range says how far a state is from pointwise incompressible. Kept per
// assembly thread and combined afterwards, so it costs two comparisons per point and no extra pass.
// Shared by iga::Problem and tet::TetProblem.
#include <span>

namespace isomuscle::continuum {

// One quadrature point's J and where it is (element, local point); element < 0: none yet.
struct JacobianAtPoint {
  double value = 0.0;
  int element = -1;
  int point = -1;

  bool found() const { return element >= 0; }
};

struct JacobianRange {
  JacobianAtPoint smallest, largest;

  bool found() const { return smallest.found(); }
  // Takes the per-point J of element e (a kernel's ElementWorkspace::J, first nqp entries).
  void take_element(int e, std::span<const double> J);
  // Takes another range. Equal values keep the smaller (element, point), so the result does not
  // depend on how elements were spread over threads.
  void take(const JacobianRange& other);
  // The range of several (e.g. one per assembly thread).
  static JacobianRange of(std::span<const JacobianRange> parts);
};

}  // namespace isomuscle::continuum
