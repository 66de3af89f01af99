#include "iga/element_kernels.hpp"

namespace isomuscle::iga {

// Views into the point-major tables of Space: R (nqp x nen), dR/dX (nqp x nen), w det J (nqp).
ElementView element_view(const Space& space, int e) {
  ElementView v;
  v.nen = space.functions_per_element();
  v.nqp = space.points_per_element();
  v.values = space.values(e, 0).data();
  v.gradients = space.gradients(e, 0).data();
  v.dv = space.element_dv(e).data();
  return v;
}

// The pressure functions N_m are the same at the points of every element (PressureSpace), the mass
// matrices M_e = int_e N N^T dV are per element.
KernelStatus mixed_kernel(const ElementView& el, const MaterialContext& mat,
                          const PressureSpace& pressure, int element, const MixedBase* base,
                          bool tangent, ElementWorkspace& ws) {
  ElementView with_pressure = el;
  with_pressure.pressure_size = pressure.size();
  with_pressure.pressure = pressure.values(0);
  return continuum::mixed_kernel(with_pressure, mat, pressure.mass(element),
                                 pressure.mass_matrix(element), base, tangent, ws);
}

}  // namespace isomuscle::iga
